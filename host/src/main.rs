//! `accelcal`: the command line of the `accelcal` library.

fn main() -> std::process::ExitCode {
    accelcal::cli::main()
}
