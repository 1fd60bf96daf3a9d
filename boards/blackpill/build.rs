fn main() {
    // NOTE: link.x comes from .cargo/config.toml for every thumbv7em build (the QEMU tests need it too).
    board_link::link(&[]);
}
