//! `accelcal`: argument parsing and wiring only; the work is in the `accelcal` library.

use std::path::PathBuf;
use std::process::ExitCode;

use accelcal::data::{Dataset, RowList};
use accelcal::fit::{self, FitOptions, ModelChoice};
use accelcal::report::{self, Comparison, FitJson};
use anyhow::Context;
use clap::{Parser, Subcommand};

/// Calibrates the accelerometer of an MPU-6050.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Fits a calibration to a calibration data file (CSV, see README).
    Fit {
        /// The data file.
        file: PathBuf,
        /// The model: auto (the richest the data supports, compared with the others),
        /// reference-norm12, linear12, ortho9, diag6 or six-position.
        #[arg(long, default_value = "auto")]
        model: ModelChoice,
        /// |gravity| in the output unit: 1 for data in g, 9.80665 (or the local value) for m/s^2.
        #[arg(long, default_value_t = 1.0)]
        g: f64,
        /// Largest tilt in degrees for a reading to count as one of the six faces.
        #[arg(long, default_value_t = FitOptions::default().face_tolerance_deg)]
        face_tolerance_deg: f64,
        /// Data rows to fit (1-based, e.g. 1-20); the others are held out and reported as test rows.
        #[arg(long)]
        rows: Option<RowList>,
        /// Data rows whose known orientation the fit uses (e.g. 1,10); the others count as |a| = g.
        #[arg(long)]
        reference_rows: Option<RowList>,
        /// Print one JSON object instead of the table.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("accelcal: {error:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Fit { file, model, g, face_tolerance_deg, rows, reference_rows, json } => {
            anyhow::ensure!(g.is_finite() && g > 0.0, "--g must be a positive number, got {g}");
            let dataset = Dataset::from_path(&file, g).with_context(|| file.display().to_string())?;
            let (training_rows, reference_rows) = (rows.map(|r| r.0), reference_rows.map(|r| r.0));
            let options = FitOptions { g, face_tolerance_deg, training_rows, reference_rows };
            let fit = fit::fit(&dataset, model, &options)
                .with_context(|| format!("{}: cannot fit {model}", file.display()))?;
            let evaluation = fit::evaluate(&dataset, &fit.matrix, &fit.offset, g, &fit.lines_used);
            let comparison = (model == ModelChoice::Auto).then(|| Comparison::new(&dataset, &options));
            if json {
                let object = FitJson::new(&fit, &evaluation, g, comparison.as_ref());
                println!("{}", serde_json::to_string_pretty(&object)?);
            } else {
                print!("{}", report::human(&fit, &dataset, &evaluation, g));
                if let Some(comparison) = &comparison {
                    print!("{}", comparison.human());
                }
            }
            Ok(())
        }
    }
}
