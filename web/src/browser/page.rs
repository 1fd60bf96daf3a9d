//! What the page shows and asks: the run's `Feedback` as calls on the page's JavaScript object.

use accelcal_core::run::Feedback;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    /// The page's object the run talks to (web/page/run.js, `pageUi`).
    #[derive(Clone)]
    pub type PageUi;
    /// A line of instruction or result.
    #[wasm_bindgen(method)]
    pub fn say(this: &PageUi, line: &str);
    /// The live state of the board (replaced by the next one).
    #[wasm_bindgen(method)]
    pub fn live(this: &PageUi, line: &str);
    /// A capture's progress, in samples.
    #[wasm_bindgen(method)]
    pub fn progress(this: &PageUi, samples: u32, total: u32);
    /// The capture ended.
    #[wasm_bindgen(method, js_name = progressDone)]
    pub fn progress_done(this: &PageUi);
    /// A yes/no question, answered before this returns.
    #[wasm_bindgen(method)]
    pub fn confirm(this: &PageUi, question: &str) -> bool;
    /// The hand's instruction: `kind` (`present`, `fresh`, `quarter`), the wanted orientation's name
    /// and up direction (empty for `fresh` and `quarter`), the verification's index, the line to show.
    #[wasm_bindgen(method)]
    pub fn prompt(this: &PageUi, kind: &str, name: &str, up: &[f64], index: u32, line: &str);
    /// Orientations (up directions, three numbers each) the fresh ones must keep away from.
    #[wasm_bindgen(method)]
    pub fn avoid(this: &PageUi, ups: &[f64]);
    /// A new hand takes the board (one for the captures, one for the verification).
    #[wasm_bindgen(method, js_name = newHand)]
    pub fn new_hand(this: &PageUi);
    /// The session as it stands, to keep (after every capture); its JSON text.
    #[wasm_bindgen(method)]
    pub fn keep(this: &PageUi, session_json: &str);
}

/// The run's feedback, shown on the page.
pub struct PageFeedback<'a>(pub &'a PageUi);

impl Feedback for PageFeedback<'_> {
    fn say(&mut self, line: &str) {
        self.0.say(line);
    }
    fn live(&mut self, line: &str) {
        self.0.live(line);
    }
    fn progress(&mut self, samples: u32, total: u32) {
        self.0.progress(samples, total);
    }
    fn progress_done(&mut self) {
        self.0.progress_done();
    }
    fn confirm(&mut self, question: &str) -> bool {
        self.0.confirm(question)
    }
}
