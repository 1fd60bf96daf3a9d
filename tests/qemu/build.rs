fn main() {
    // NOTE: link.x comes from .cargo/config.toml for every thumbv7em build.
    board_link::link(&[]);
}
