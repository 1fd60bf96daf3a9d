fn main() {
    // NOTE: esp-hal brings the ESP32-C3's memory map and sections; linkall.x includes them.
    board_link::link(&["-Tlinkall.x"]);
}
