//! The WebAssembly exports a page (and `tests/run.mjs`) calls, without wasm-bindgen: numbers in and
//! out, the result's text left in this module's memory for the caller to read. They build natively
//! too, where the tests call them directly.

use std::cell::RefCell;

thread_local! {
    /// The last result's UTF-8 bytes, kept until the next call so the caller can read them.
    // NOTE: thread_local, not `static mut`: safe to borrow, and on wasm32 (one thread) just a static.
    static RESULT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// Computes [`crate::simulated_session_json`] for the seed `seed_high << 32 | seed_low` into the result
/// buffer and returns its length in bytes; read it at [`result_ptr`].
// NOTE: the seed comes in 32-bit halves: a u64 would be a BigInt in JavaScript, awkward for a page.
#[no_mangle]
pub extern "C" fn simulated_session(seed_low: u32, seed_high: u32) -> u32 {
    let seed = (u64::from(seed_high) << 32) | u64::from(seed_low);
    keep(crate::simulated_session_json(seed).into_bytes())
}

/// Where the last result's bytes start in this module's memory (its length is the last call's answer).
#[no_mangle]
pub extern "C" fn result_ptr() -> *const u8 {
    RESULT.with(|result| result.borrow().as_ptr())
}

/// Keeps `bytes` as the result; returns their length.
fn keep(bytes: Vec<u8>) -> u32 {
    // NOTE: a length never passes u32 on wasm32, where usize is 32 bits; a result of 4 GiB natively is
    // out of the question (a calibration's JSON is about a kilobyte).
    let len = bytes.len() as u32;
    RESULT.with(|result| *result.borrow_mut() = bytes);
    len
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bytes the last call left, read as the JavaScript side reads them: from the pointer and length.
    fn read_result(len: u32) -> String {
        // SAFETY: `result_ptr` points at the buffer `keep` filled with `len` bytes; nothing else
        // touches it until the next call.
        let bytes = unsafe { std::slice::from_raw_parts(result_ptr(), len as usize) };
        String::from_utf8(bytes.to_vec()).expect("the result is UTF-8 text")
    }

    #[test]
    fn export_leaves_the_json_at_result_ptr() {
        let len = simulated_session(7, 0);
        assert_eq!(read_result(len), crate::simulated_session_json(7));
    }

    #[test]
    fn export_joins_the_seed_halves_high_then_low() {
        let len = simulated_session(1, 2);
        assert_eq!(read_result(len), crate::simulated_session_json((2 << 32) | 1));
        assert_ne!(read_result(len), crate::simulated_session_json((1 << 32) | 2));
    }
}
