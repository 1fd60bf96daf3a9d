fn main() {
    // NOTE: link-rp.x places the RP2040's second-stage bootloader in BOOT2; the RP2350 boots from the
    // IMAGE_DEF block its memory map places after the vector table.
    if std::env::var_os("CARGO_FEATURE_PICO2").is_some() {
        board_link::link_memory("memory-rp2350.x", &["--nmagic", "-Tlink.x"]);
    } else {
        board_link::link_memory("memory-rp2040.x", &["--nmagic", "-Tlink.x", "-Tlink-rp.x"]);
    }
}
