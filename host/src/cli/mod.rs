//! The command line: arguments ([`args`]), and one file per command group: offline fits
//! ([`fit`]), the guided procedure ([`procedure`]), moving calibrations to and from the board
//! ([`transfer`]), the board itself ([`board`]), noise of a recording ([`noise`]); [`device`] opens the board each command names.

pub mod args;
mod board;
mod calibrate;
mod certificate;
mod device;
mod export;
mod fit;
mod fixture;
mod foreign;
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
mod thermal;
mod transfer;
mod values;

use std::process::ExitCode;

use clap::Parser;

use crate::error::Error;
use args::{CalibrateArgs, Cli, Command};

/// Runs `accelcal` with the process's arguments: 0 on success, else one line naming the cause and
/// 1 (2: a calibration uploaded and saved that missed `--target-mg` by more than its noise).
pub fn main() -> ExitCode {
    crate::terminal::end_quietly_when_the_reader_goes_away();
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("accelcal: {error}");
            ExitCode::from(error.exit_code())
        }
    }
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
        Command::Web { dir, port } => serve_page(&dir, port),
        Command::Sim { pty: true, seed, sketch: Some(sketch), .. } => {
            Ok(crate::sim::replay::serve_replay(sketch, seed)?)
        }
        Command::Sim { seed, sketch: Some(sketch), .. } => crate::sim::replay::print_log(sketch, seed)
            .map_err(|source| Error::WriteFile { path: "stdout".into(), source }),
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
/// `accelcal web`: serves the page until killed, its address printed first.
fn serve_page(dir: &std::path::Path, port: u16) -> Result<(), Error> {
    let server = crate::web::PageServer::bind(dir, port)?;
    println!("serving {} on {} (Ctrl-C ends it); open it in Chrome, Edge or Opera", dir.display(), server.url());
    server.serve();
    Ok(())
}

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
    let mut feedback = crate::terminal::feedback(args.json && simulated, args.yes || (args.json && simulated));
    let Some(report) =
        calibrate::calibrate_board(args, opened, crate::terminal::interrupt_on_ctrl_c(), feedback.as_mut())?
    else {
        return Ok(());
    };
    calibrate::show(&report, args.json)?;
    let kept = args.session.is_some() || !simulated;
    crate::ended::what_next(simulated, kept).iter().for_each(|line| feedback.say(line));
    Ok(())
}
