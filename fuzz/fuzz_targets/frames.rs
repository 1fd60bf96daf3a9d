//! Arbitrary bytes into the device's serial link: the frame decoder and the request handler must
//! never panic, never hang, answer only with frame errors unless the bytes hold a valid frame, and
//! leave the device answering a well-formed hello.
#![no_main]

use embassy_futures::block_on;
use firmware::device::Device;
use firmware::link::Link;
use firmware::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};
use libfuzzer_sys::fuzz_target;
use shared::protocol::{self, Request, Response, MAX_FRAME_LEN, PROTOCOL_VERSION};

fuzz_target!(|bytes: &[u8]| {
    let Ok(mut device) = block_on(Device::boot(SimMpu6050::new(1), SimFlash::new(), SIM_FLASH_RANGE, sim_serial_number(1))) else {
        return;
    };
    let mut link = Link::new();
    for chunk in bytes.chunks(64) {
        block_on(link.receive(chunk, &mut device));
        device.bus_mut().advance_us(10_000);
        device.poll();
        while device.next_response().is_some() {}
    }
    // Whatever came before, a delimiter and a hello get a hello back.
    let mut frame = [0u8; MAX_FRAME_LEN];
    let len = protocol::encode(7, &Request::Hello { protocol_version: PROTOCOL_VERSION }, &mut frame).unwrap();
    block_on(link.receive(&[0], &mut device));
    block_on(link.receive(&frame[..len], &mut device));
    let mut answered = false;
    while let Some((id, response)) = device.next_response() {
        answered |= id == 7 && matches!(response, Response::Hello(_));
    }
    assert!(answered, "the device stopped answering");
});
