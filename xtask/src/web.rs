//! `cargo xtask web`: the web page (issue 37) as one static folder: accelcal-web built for
//! wasm32-unknown-unknown with the size-minded `web` profile, its JavaScript glue written by
//! wasm-bindgen (the CLI of the very version Cargo.lock holds; `.ci/run` installs it), and the page's
//! own files from web/page. Nothing in it is fetched from elsewhere at run time.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};

/// The page's files beside the wasm, copied as they are.
const PAGE_DIR: &str = "web/page";
/// What wasm-bindgen names the module and its glue (the crate's library name).
const MODULE: &str = "accelcal_web";

/// Builds the page into `<target dir>/web` and prints its size; the folder.
pub fn build(root: &Path) -> Result<PathBuf> {
    let target = target_dir(root);
    cargo_build(root)?;
    let out = target.join("web");
    if out.exists() {
        std::fs::remove_dir_all(&out).with_context(|| format!("clearing {}", out.display()))?;
    }
    let wasm = target.join("wasm32-unknown-unknown/web/accelcal_web.wasm");
    bindgen(root, &wasm, &out.join("pkg"))?;
    copy_page(&root.join(PAGE_DIR), &out)?;
    report_size(&out)?;
    copy_images(&root.join("dist"), &out)?;
    Ok(out)
}

/// The Cargo target directory: CARGO_TARGET_DIR (relative to the workspace) or the workspace's own.
pub fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), |dir| root.join(dir))
}

fn cargo_build(root: &Path) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    eprintln!("== web: cargo build -p accelcal-web --target wasm32-unknown-unknown --profile web");
    let status = Command::new(cargo)
        .current_dir(root)
        .args(["build", "-p", "accelcal-web", "--lib", "--target", "wasm32-unknown-unknown", "--profile", "web"])
        .status()
        .context("running cargo build")?;
    if !status.success() {
        bail!("the wasm build failed (is the target installed? rustup target add wasm32-unknown-unknown)");
    }
    Ok(())
}

/// The version of wasm-bindgen Cargo.lock holds, which the CLI must match exactly.
fn locked_bindgen_version(root: &Path) -> Result<String> {
    let lock = std::fs::read_to_string(root.join("Cargo.lock")).context("reading Cargo.lock")?;
    let mut lines = lock.lines();
    while let Some(line) = lines.next() {
        if line == "name = \"wasm-bindgen\"" {
            let version = lines.next().and_then(|l| l.strip_prefix("version = \"")).and_then(|v| v.strip_suffix('"'));
            return version.map(str::to_owned).context("Cargo.lock's wasm-bindgen entry has no version line");
        }
    }
    bail!("Cargo.lock holds no wasm-bindgen")
}

/// Writes the module and its JavaScript glue (ES module, for `<script type="module">` and workers).
fn bindgen(root: &Path, wasm: &Path, out: &Path) -> Result<()> {
    let wanted = locked_bindgen_version(root)?;
    let install = format!("cargo install --locked wasm-bindgen-cli --version {wanted}");
    let found = Command::new("wasm-bindgen")
        .arg("--version")
        .output()
        .with_context(|| format!("wasm-bindgen is not installed: {install}"))?;
    let found = String::from_utf8_lossy(&found.stdout).trim().to_owned();
    if found.split_whitespace().nth(1) != Some(wanted.as_str()) {
        bail!("{found} does not match the crate's wasm-bindgen {wanted}: {install}");
    }
    let status = Command::new("wasm-bindgen")
        .args(["--target", "web", "--no-typescript", "--out-name", MODULE, "--out-dir"])
        .args([out, wasm])
        .status()
        .context("running wasm-bindgen")?;
    if !status.success() {
        bail!("wasm-bindgen failed on {}", wasm.display());
    }
    Ok(())
}

/// Copies the page's files (one level: the page has no subfolders) into `out`.
fn copy_page(page: &Path, out: &Path) -> Result<()> {
    for entry in std::fs::read_dir(page).with_context(|| format!("reading {}", page.display()))? {
        let path = entry?.path();
        if path.is_file() {
            let to = out.join(path.file_name().context("a file has a name")?);
            std::fs::copy(&path, &to).with_context(|| format!("copying {} to {}", path.display(), to.display()))?;
        }
    }
    Ok(())
}

/// The board images the page's flashing steps offer, as `cargo xtask dist` writes them.
const IMAGES: [&str; 5] = [
    "accelcal-pico.uf2",
    "accelcal-pico2.uf2",
    "accelcal-blackpill-f411.bin",
    "accelcal-blackpill-f401.bin",
    "accelcal-esp32c3.bin",
];

/// Copies the board images from `dist` into the page (after its size is measured: they are downloads,
/// never loaded by the page); says which are missing (`cargo xtask dist` writes them).
fn copy_images(dist: &Path, out: &Path) -> Result<()> {
    let missing: Vec<&str> = IMAGES.into_iter().filter(|name| !dist.join(name).is_file()).collect();
    for name in IMAGES.iter().filter(|name| !missing.contains(name)) {
        std::fs::copy(dist.join(name), out.join(name)).with_context(|| format!("copying {name}"))?;
    }
    if !missing.is_empty() {
        eprintln!("web: without {} (run `cargo xtask dist` first to offer them on the page)", missing.join(", "));
    }
    Ok(())
}

/// Prints the folder's size, raw and gzipped (the wasm and the JavaScript, which the page loads).
fn report_size(out: &Path) -> Result<()> {
    let mut total = (0usize, 0usize);
    for path in files(out)? {
        let bytes = std::fs::read(&path)?;
        let gzipped = gzip_size(&bytes)?;
        eprintln!("  {:>9} bytes, {:>8} gzipped  {}", bytes.len(), gzipped, path.strip_prefix(out)?.display());
        total = (total.0 + bytes.len(), total.1 + gzipped);
    }
    eprintln!("web: {} bytes, {} gzipped, in {}", total.0, total.1, out.display());
    Ok(())
}

fn files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        match path.is_dir() {
            true => found.extend(files(&path)?),
            false => found.push(path),
        }
    }
    found.sort();
    Ok(found)
}

/// The size of `bytes` gzipped at the best level, as a server would send them (the system's gzip).
fn gzip_size(bytes: &[u8]) -> Result<usize> {
    use std::io::Write;
    use std::process::Stdio;
    let mut gzip = Command::new("gzip")
        .args(["-9", "-c"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .context("running gzip, which measures the page's size")?;
    // NOTE: written from a thread, so that gzip filling its output pipe cannot wait on this one.
    let mut stdin = gzip.stdin.take().context("gzip's stdin")?;
    let input = bytes.to_vec();
    let writer = std::thread::spawn(move || stdin.write_all(&input));
    let output = gzip.wait_with_output()?;
    writer.join().map_err(|_| anyhow::anyhow!("writing to gzip panicked"))??;
    Ok(output.stdout.len())
}
