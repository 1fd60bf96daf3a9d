//! The page's side of the browser: the core's board run driven over a port the page opened with Web
//! Serial ([`transport`]), told to the page ([`page`]), with the person's hand as prompts the page
//! shows ([`hand`]); the simulated board a Web Worker serves behind a simulated port ([`simulated`]);
//! and a sketch's log fitted as `accelcal fit LOG` fits it ([`fit_log`]).
//! Every item here is called from JavaScript through wasm-bindgen (web/page/*.js).

pub mod board_run;
pub mod fit_log;
pub mod hand;
pub mod page;
pub mod simulated;
pub mod transport;
