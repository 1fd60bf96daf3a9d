//! The command line: arguments ([`args`]), and one file per command group: offline fits
//! ([`fit`]), the guided procedure ([`procedure`]), moving calibrations to and from the board
//! ([`transfer`]), the board itself ([`board`]), noise of a recording ([`noise`]); [`device`] opens the board each command names.

mod adaptive;
pub mod args;
mod board;
mod calibrate;
mod certificate;
mod device;
mod export;
mod fit;
mod fixture;
mod foreign;
mod kept;
mod length;
mod lot;
mod named;
mod noise;
mod overwrite;
mod procedure;
mod record;
mod repeat;
mod report;
mod selftest;
mod terminal;
mod thermal;
mod transfer;
mod values;

use std::process::ExitCode;

use clap::Parser;

use crate::error::Error;
use args::{CalibrateArgs, Cli, Command};

pub use terminal::Terminal;

/// Runs `accelcal` with the process's arguments: 0 on success, else one line naming the cause and
/// 1 (2: a calibration uploaded and saved that missed `--target-mg` by more than its noise).
pub fn main() -> ExitCode {
    end_quietly_when_the_reader_goes_away();
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("accelcal: {error}");
            ExitCode::from(error.exit_code())
        }
    }
}

/// Exit status when whoever read the output went away (`| head`): 128 + SIGPIPE, what a shell
/// reports for a Unix tool that a closed pipe ended.
pub const READER_GONE_EXIT: i32 = 141;

/// Ends the process at once, with [`READER_GONE_EXIT`] and no message, when printing to standard
/// output fails because its reader closed the pipe: `println!` panics then, which is no fault of
/// the command's. Every file a command writes is written before it prints, and a session file
/// after each capture, so nothing is lost that was not already going to the closed pipe.
// NOTE: Rust ignores SIGPIPE so that a write fails instead; restoring the signal's default would
// also end the process silently when a child it pipes to (the emulated Pico) dies, which must be
// named instead.
fn end_quietly_when_the_reader_goes_away() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info.payload_as_str().unwrap_or_default();
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(READER_GONE_EXIT);
        }
        default(info);
    }));
}

/// Runs one command.
pub fn run(cli: Cli) -> Result<(), Error> {
    match cli.command {
        Command::Fit(args) => fit::fit(&args),
        Command::Ports => board::ports(),
        Command::Info { device, json, registers } => board::info(&device, json, registers),
        Command::Calibrate(args) => calibrate(&args),
        Command::Capture(args) => procedure::capture(&args),
        Command::Report(args) => report::report(&args),
        Command::Certificate(args) => certificate::certificate(&args),
        Command::Lot(args) => lot::lot(&args),
        Command::Repeat(args) => repeat::repeat(&args),
        Command::Verify { device, positions } => procedure::verify(&device, usize::from(positions)),
        Command::Upload { device, file, save } => transfer::upload(&device, &file, save),
        Command::Save { device } => transfer::save(&device),
        Command::Download { device, stored } => transfer::download(&device, stored),
        Command::Erase { device } => transfer::erase(&device),
        Command::Stream(args) => board::stream(&args),
        Command::Noise(args) => noise::noise(&args),
        Command::Export(args) => export::export(&args),
        Command::Record(args) => record::record(&args),
        Command::Thermal(args) => thermal::thermal(&args),
        Command::Selftest(args) => selftest::selftest(&args),
        Command::Sim { pty, seed, sketch: Some(sketch), .. } => sketch_stream(sketch, seed, pty),
        Command::Sim { seed, pico: Some(uf2), .. } => {
            Ok(crate::sim::serve_emulated(&uf2, seed, crate::sim::SimSensor::Realistic)?)
        }
        Command::Sim { pty: _, seed, fast, sketch: None, pico: None } => {
            let pace = if fast { crate::sim::Pace::Fast } else { crate::sim::Pace::RealTime };
            Ok(crate::sim::serve_pty(seed, pace)?)
        }
    }
}

/// `accelcal calibrate`: captures, fit, upload, save, verification; several boards on one fixture
/// together.
fn calibrate(args: &CalibrateArgs) -> Result<(), Error> {
    // NOTE: refused before anything happens: a run that could only end without the upload it was
    // asked for must not start (the simulated board, turned by the tool itself, needs no answer).
    if args.json && !args.yes && !args.device.sim {
        return Err(Error::JsonCannotAsk);
    }
    if fixture::holds_several(args) {
        return fixture::calibrate_together(args);
    }
    let opened = match args.device.open_or_talking()? {
        Ok(opened) => opened,
        Err(talking) => return foreign::calibrate_from_stream(args, *talking),
    };
    // NOTE: with --json only the simulated board (turned by the tool) is silent: a person at a real
    // board still needs the instructions, which go to stderr, leaving stdout to the JSON.
    let simulated = opened.sim.is_some();
    let mut feedback = terminal::feedback(args.json && simulated, args.yes || (args.json && simulated));
    match calibrate::calibrate_board(args, opened, terminal::interrupt_on_ctrl_c(), feedback.as_mut())? {
        Some(report) => calibrate::show(&report, args.json),
        None => Ok(()),
    }
}

/// `sim --sketch`: the replay on a pseudo-terminal, or the whole log on stdout.
fn sketch_stream(sketch: crate::sim::sketch::Sketch, seed: u64, pty: bool) -> Result<(), Error> {
    if pty {
        return Ok(crate::sim::replay::serve_replay(sketch, seed)?);
    }
    let session = crate::sim::person::PersonSession::new(seed, sketch.reading());
    let mut out = std::io::stdout().lock();
    for line in sketch.lines(&session) {
        std::io::Write::write_all(&mut out, line.text.as_bytes())
            .map_err(|source| Error::WriteFile { path: "stdout".into(), source })?;
    }
    Ok(())
}
