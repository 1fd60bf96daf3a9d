//! The simulated person and sketches, the hand that turns a simulated board and the board itself in
//! this process, random draws and synthetic data sets: for tests and the simulated runs (house rule 13: simulated things live in `sim`).

pub mod board;
mod command;
pub mod motion;
mod owner_hand;
pub mod person;
pub mod random;
pub mod sessions;
mod simulated_hand;
mod simulated_session;
pub mod sketch;
pub mod synthetic;
pub mod turn;

pub use board::{BoardControls, InProcess};
pub use command::SimCommand;
pub use owner_hand::OwnerHand;
pub use simulated_hand::{Controls, SimulatedHand, Stopped, VERIFICATION_TURN_DEG};
pub use simulated_session::{SimulatedBoard, SimulatedSession};
