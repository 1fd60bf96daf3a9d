//! The core's `Transport` over the page's port object (web/page/port.js): bytes written and read
//! through its promises, its clocks, and the person's Stop.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use accelcal_core::link::{LinkError, Transport};
use accelcal_core::run::BoardClock;
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

#[wasm_bindgen]
extern "C" {
    /// The page's port (web/page/port.js, `PagePort`): a Web Serial port, or the simulated one.
    pub type PagePort;
    /// Writes the bytes; resolves once they are handed to the port, rejects when it is gone.
    #[wasm_bindgen(method)]
    pub fn write(this: &PagePort, bytes: &[u8]) -> js_sys::Promise;
    /// Resolves with what arrived (a Uint8Array, empty when nothing came within a short while);
    /// rejects when the port is gone.
    #[wasm_bindgen(method)]
    pub fn read(this: &PagePort) -> js_sys::Promise;
    /// The host's time since the port was opened, in seconds.
    #[wasm_bindgen(method, js_name = nowSeconds)]
    pub fn now_seconds(this: &PagePort) -> f64;
    /// The date now, in seconds since the Unix epoch.
    #[wasm_bindgen(method, js_name = unixTimeSeconds)]
    pub fn unix_time_seconds(this: &PagePort) -> f64;
    /// The board's clock in seconds: its own for a simulated board, else the host's since it was opened.
    #[wasm_bindgen(method, js_name = boardSeconds)]
    pub fn board_seconds(this: &PagePort) -> f64;
    /// Whether the person pressed Stop.
    #[wasm_bindgen(method)]
    pub fn interrupted(this: &PagePort) -> bool;
}

/// The transport to the board behind the page's port.
pub struct PageTransport {
    port: PagePort,
    /// What the last read brought beyond what the link took.
    pending: Vec<u8>,
    /// The board's clock as of the last read, as f64 bits (the run's clock reads it).
    board_s: Arc<AtomicU64>,
}

impl PageTransport {
    /// A transport over `port`.
    pub fn new(port: PagePort) -> Self {
        let board_s = Arc::new(AtomicU64::new(port.board_seconds().to_bits()));
        PageTransport { port, pending: Vec::new(), board_s }
    }

    /// The board's clock, as the run reads it: the board's time as of the last read.
    // NOTE: read from the last read, not from the port: the run's clock must be `Send + Sync`, which a
    // JavaScript object is not; a simulated board's time moves only on reads anyway.
    pub fn clock(&self) -> BoardClock {
        let board_s = self.board_s.clone();
        Arc::new(move || f64::from_bits(board_s.load(Ordering::Relaxed)))
    }
}

/// The port's error as the link names a board that went away.
fn gone(error: JsValue) -> LinkError {
    let why = error.as_string().or_else(|| js_sys::Error::from(error).message().as_string()).unwrap_or_default();
    LinkError::Disconnected { reason: if why.is_empty() { "the port closed".to_owned() } else { why } }
}

impl Transport for PageTransport {
    async fn write(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        JsFuture::from(self.port.write(bytes)).await.map(|_| ()).map_err(gone)
    }

    async fn read(&mut self, buffer: &mut [u8]) -> Result<usize, LinkError> {
        if self.pending.is_empty() {
            let chunk = JsFuture::from(self.port.read()).await.map_err(gone)?;
            self.pending = js_sys::Uint8Array::new(&chunk).to_vec();
            self.board_s.store(self.port.board_seconds().to_bits(), Ordering::Relaxed);
        }
        let n = buffer.len().min(self.pending.len());
        buffer[..n].copy_from_slice(&self.pending[..n]);
        self.pending.drain(..n);
        Ok(n)
    }

    fn now(&self) -> Duration {
        Duration::from_secs_f64(self.port.now_seconds().max(0.0))
    }

    fn unix_time_s(&self) -> f64 {
        self.port.unix_time_seconds()
    }

    fn interrupted(&self) -> bool {
        self.port.interrupted()
    }
}
