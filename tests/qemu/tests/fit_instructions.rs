//! How many instructions the chip's `ortho9` fit of ten captures takes on an emulated Cortex-M4F:
//! QEMU runs `fit-count` one instruction per translation block (`-singlestep`) and logs every block it
//! executes (`-d exec,nochain`); the count is the log's lines between the two calls of the binary's
//! marker, calls of libm, memcpy and the FPU's square root included. QEMU emulates no cycle counter,
//! so this is instructions, not cycles. Needs what tests/on_target.rs needs.

mod common;

use std::process::Command;

/// The most instructions the fit of ten captures may take (issue 29: 58 400 before the FPU's square
/// root and without copying 9x9 systems; about 31 000 without both).
const MOST_INSTRUCTIONS: usize = 35_000;

#[test]
#[cfg_attr(not(on_target_runnable), ignore = "needs qemu-system-arm and the on-target binaries (tests/qemu/build.rs)")]
fn the_chip_s_ortho9_fit_of_ten_captures_takes_at_most_35_000_instructions() {
    let elf = common::runnable("fit-count");
    let log = std::env::temp_dir().join(format!("accelcal-fit-count-{}.log", std::process::id()));
    let output = Command::new("qemu-system-arm")
        .args(["-machine", "netduinoplus2", "-nographic", "-semihosting-config", "enable=on,target=native"])
        .args(["-singlestep", "-d", "exec,nochain", "-D"])
        .arg(&log)
        .arg("-kernel")
        .arg(&elf)
        .output()
        .expect("qemu runs");
    let trace = std::fs::read_to_string(&log).expect("QEMU wrote its trace");
    let _ = std::fs::remove_file(&log);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success() && text.lines().any(|l| l == "done"), "on target:\n{text}");
    let marker = text.lines().find_map(|l| l.strip_prefix("marker 0x")).expect("the marker's address");
    // NOTE: a logged block reads "Trace 0: host [flags/pc/flags/flags] symbol"; the pc has 8 digits.
    let at_marker = format!("/{marker:0>8}/");
    let calls: Vec<usize> = trace.lines().enumerate().filter(|(_, l)| l.contains(&at_marker)).map(|(i, _)| i).collect();
    assert_eq!(calls.len(), 2, "the marker runs before and after the fit");
    let instructions = calls[1] - calls[0];
    let iterations = text.lines().find_map(|l| l.strip_prefix("iterations ")).unwrap_or("?");
    println!("the chip's ortho9 fit of ten captures: {instructions} instructions, {iterations} iterations");
    assert!(instructions > 5_000, "{instructions} instructions cannot be a fit");
    assert!(instructions <= MOST_INSTRUCTIONS, "{instructions} instructions, more than {MOST_INSTRUCTIONS}");
}
