//! `accelcal web`: the web page (`cargo xtask web`'s folder, docs/web.md) served on localhost, where a
//! browser grants it Web Serial (a secure context). A static file server on std::net: GET only, files
//! under the folder only, one connection at a time (one person's browser).

use std::io::{BufRead, BufReader, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Component, Path, PathBuf};

/// Where `cargo xtask web` writes the page, from the workspace's root.
pub const BUILT_PAGE: &str = "target/web";

/// Why the page cannot be served.
#[derive(Debug, thiserror::Error)]
pub enum WebError {
    #[error("{} holds no index.html: build the page with `cargo xtask web` (docs/web.md), or give --dir", .0.display())]
    NoPage(PathBuf),
    #[error("cannot listen on 127.0.0.1:{port}: {source}; give another --port (0 picks a free one)")]
    Listen { port: u16, source: std::io::Error },
}

/// The page's folder, listening on 127.0.0.1:`port`.
pub struct PageServer {
    dir: PathBuf,
    listener: TcpListener,
}

impl PageServer {
    /// Listens on 127.0.0.1:`port` (0: a free one) for the page in `dir`.
    pub fn bind(dir: &Path, port: u16) -> Result<Self, WebError> {
        if !dir.join("index.html").is_file() {
            return Err(WebError::NoPage(dir.to_path_buf()));
        }
        let listener = TcpListener::bind(("127.0.0.1", port)).map_err(|source| WebError::Listen { port, source })?;
        Ok(PageServer { dir: dir.to_path_buf(), listener })
    }

    /// The address a browser opens.
    pub fn url(&self) -> String {
        let port = self.listener.local_addr().map(|a| a.port()).unwrap_or_default();
        format!("http://localhost:{port}/")
    }

    /// Serves until the process ends; a connection that fails is dropped, the next one served.
    pub fn serve(&self) {
        for stream in self.listener.incoming().flatten() {
            // NOTE: a browser that closed its connection mid-answer is no reason to stop serving.
            let _ = self.answer(stream);
        }
    }

    /// Answers one request: the file it names, 404 for one outside the folder or missing, 405 for
    /// anything but GET and HEAD.
    fn answer(&self, mut stream: TcpStream) -> std::io::Result<()> {
        let mut line = String::new();
        BufReader::new(&stream).read_line(&mut line)?;
        let mut words = line.split_whitespace();
        let (method, target) = (words.next().unwrap_or(""), words.next().unwrap_or("/"));
        if method != "GET" && method != "HEAD" {
            return respond(&mut stream, "405 Method Not Allowed", "text/plain", b"GET only", false);
        }
        match self.file(target).and_then(|path| Some((std::fs::read(&path).ok()?, content_type(&path)))) {
            Some((body, kind)) => respond(&mut stream, "200 OK", kind, &body, method == "HEAD"),
            None => respond(&mut stream, "404 Not Found", "text/plain", b"not found", method == "HEAD"),
        }
    }

    /// The file a request's path names inside the folder; none for one that leaves it.
    fn file(&self, target: &str) -> Option<PathBuf> {
        let path = target.split(['?', '#']).next().unwrap_or("/");
        let relative = Path::new(path.trim_start_matches('/'));
        if !relative.components().all(|c| matches!(c, Component::Normal(_))) {
            return None;
        }
        let file = self.dir.join(relative);
        Some(if path.ends_with('/') || path.is_empty() { file.join("index.html") } else { file })
    }
}

/// Writes an HTTP/1.1 answer and closes the connection.
fn respond(stream: &mut TcpStream, status: &str, kind: &str, body: &[u8], head: bool) -> std::io::Result<()> {
    let header = format!(
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nCache-Control: no-cache\r\nConnection: close\r\n\r\n",
        body.len()
    );
    stream.write_all(header.as_bytes())?;
    if !head {
        stream.write_all(body)?;
    }
    stream.flush()
}

/// The content type of a page file, by its extension: the module scripts and the wasm must be
/// served as what they are (a browser refuses a module script of another type).
fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()).unwrap_or("") {
        "html" => "text/html; charset=utf-8",
        "js" => "text/javascript; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "wasm" => "application/wasm",
        "json" => "application/json",
        _ => "application/octet-stream",
    }
}

#[cfg(test)]
mod tests {
    use std::io::Read;

    use super::*;

    /// A folder with a page in it, under the system's temporary folder.
    fn page_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("accelcal-web-{name}-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("pkg")).unwrap();
        std::fs::write(dir.join("index.html"), "<!doctype html><title>page</title>").unwrap();
        std::fs::write(dir.join("pkg/m.wasm"), [0u8, 0x61, 0x73, 0x6d]).unwrap();
        dir
    }

    /// What the server answers to `request`, served on a thread.
    fn ask(server: PageServer, request: &str) -> Vec<u8> {
        let address = server.listener.local_addr().unwrap();
        std::thread::spawn(move || server.serve());
        let mut stream = TcpStream::connect(address).unwrap();
        stream.write_all(request.as_bytes()).unwrap();
        let mut answer = Vec::new();
        stream.read_to_end(&mut answer).unwrap();
        answer
    }

    #[test]
    fn the_page_s_files_are_served_with_their_types_and_nothing_outside_the_folder() {
        let dir = page_dir("serve");
        let index = ask(PageServer::bind(&dir, 0).unwrap(), "GET / HTTP/1.1\r\n\r\n");
        let index = String::from_utf8(index).unwrap();
        assert!(index.starts_with("HTTP/1.1 200 OK\r\nContent-Type: text/html"), "{index}");
        assert!(index.ends_with("\r\n\r\n<!doctype html><title>page</title>"), "{index}");
        let wasm = ask(PageServer::bind(&dir, 0).unwrap(), "GET /pkg/m.wasm?v=1 HTTP/1.1\r\n\r\n");
        assert!(wasm.starts_with(b"HTTP/1.1 200 OK\r\nContent-Type: application/wasm\r\nContent-Length: 4\r\n"));
        assert!(wasm.ends_with(&[0u8, 0x61, 0x73, 0x6d]));
        let outside = ask(PageServer::bind(&dir, 0).unwrap(), "GET /pkg/../../secret HTTP/1.1\r\n\r\n");
        assert!(outside.starts_with(b"HTTP/1.1 404 Not Found"), "{}", String::from_utf8_lossy(&outside));
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn a_folder_without_the_page_is_refused_naming_the_command_that_builds_it() {
        let dir = std::env::temp_dir().join(format!("accelcal-web-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let error = PageServer::bind(&dir, 0).err().expect("refused").to_string();
        assert!(error.contains("holds no index.html: build the page with `cargo xtask web`"), "{error}");
        let _ = std::fs::remove_dir_all(dir);
    }
}
