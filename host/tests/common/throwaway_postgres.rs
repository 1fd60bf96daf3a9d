//! A throwaway PostgreSQL server for the lot's tests (issue 41): a cluster made by the system's own
//! `initdb` in a temporary folder, started with `pg_ctl` on a free local port (TCP on 127.0.0.1 only,
//! its socket in that folder), stopped and removed when dropped. Nothing is mocked.
//!
//! NOTE: initdb and the server refuse to run as root (CI runs as root), so there they run as
//! `nobody` (setpriv, util-linux), in a folder that user owns; as anyone else they run as that user.

use std::net::TcpListener;
use std::os::unix::fs::PermissionsExt;
use std::path::PathBuf;
use std::process::{Command, Output};

/// The user a root process runs the server as (`nobody` on Debian).
const UNPRIVILEGED_ID: u32 = 65534;

/// A running throwaway server.
pub struct Server {
    dir: PathBuf,
    bin: PathBuf,
    pub port: u16,
}

impl Server {
    /// Makes and starts a new cluster; panics naming what failed (a test cannot go on without it).
    pub fn start(name: &str) -> Server {
        let dir = std::env::temp_dir().join(format!("accelcal-pg-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700)).unwrap();
        if is_root() {
            std::os::unix::fs::chown(&dir, Some(UNPRIVILEGED_ID), Some(UNPRIVILEGED_ID)).unwrap();
        }
        let port = TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
        let server = Server { dir, bin: bin_dir(), port };
        let data = server.data();
        let init = ["-D", &data, "-U", "accelcal", "--auth=trust", "-E", "UTF8", "--no-sync"];
        server.run("initdb", &init);
        server.restart();
        server
    }

    /// The lot's address on this server.
    pub fn url(&self) -> String {
        format!("postgres://accelcal@127.0.0.1:{}/postgres", self.port)
    }

    /// Starts the server (again), waiting until it takes connections.
    pub fn restart(&self) {
        let options =
            format!("-p {} -k {} -c listen_addresses=127.0.0.1 -c max_connections=60", self.port, self.dir.display());
        let log = self.dir.join("server.log");
        self.run("pg_ctl", &["-D", &self.data(), "-l", &log.to_string_lossy(), "-w", "-o", &options, "start"]);
    }

    /// Stops the server as an operator would (`pg_ctl stop -m fast`: connections cut, nothing lost).
    pub fn stop(&self) {
        self.run("pg_ctl", &["-D", &self.data(), "-w", "-m", "fast", "stop"]);
    }

    /// A client of the lot's database, for the tests' own statements.
    pub fn client(&self) -> postgres::Client {
        postgres::Client::connect(&self.url(), postgres::NoTls).unwrap()
    }

    fn data(&self) -> String {
        self.dir.join("data").to_string_lossy().into_owned()
    }

    /// Runs one of the server's programs, which must succeed.
    fn run(&self, program: &str, args: &[&str]) -> Output {
        let output = self.command(program).args(args).output().unwrap();
        assert!(
            output.status.success(),
            "{program} {args:?} failed: {}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
        output
    }

    /// One of the server's programs, as `nobody` when this process is root.
    fn command(&self, program: &str) -> Command {
        let program = self.bin.join(program);
        let mut command = match is_root() {
            true => {
                let mut command = Command::new("setpriv");
                let id = UNPRIVILEGED_ID.to_string();
                command.args(["--reuid", &id, "--regid", &id, "--clear-groups"]).arg(&program);
                command
            }
            false => Command::new(&program),
        };
        command.env("HOME", &self.dir);
        command
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.command("pg_ctl").args(["-D", &self.data(), "-m", "immediate", "stop"]).output();
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Whether this process runs as root (`/proc/self` belongs to the process's effective user).
fn is_root() -> bool {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata("/proc/self").is_ok_and(|m| m.uid() == 0)
}

/// The newest PostgreSQL's programs (Debian keeps them in /usr/lib/postgresql/VERSION/bin), else
/// the folder of `initdb` on the PATH.
fn bin_dir() -> PathBuf {
    let mut versions: Vec<(u32, PathBuf)> = std::fs::read_dir("/usr/lib/postgresql")
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok())
        .filter_map(|e| Some((e.file_name().to_str()?.parse().ok()?, e.path().join("bin"))))
        .filter(|(_, bin): &(u32, PathBuf)| bin.join("initdb").exists())
        .collect();
    versions.sort();
    if let Some((_, bin)) = versions.pop() {
        return bin;
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    let found = std::env::split_paths(&path).find(|dir| dir.join("initdb").exists());
    found.unwrap_or_else(|| panic!("no PostgreSQL server here: install Debian's postgresql (.ci/run does)"))
}
