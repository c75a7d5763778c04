//! Helpers shared by the viewer's integration tests: recording runs, a server on a thread and
//! a raw HTTP client.

#![allow(dead_code)]

pub mod ledges;
pub mod resting;
pub mod slots;
pub mod walls;
// One copy of the scratch-directory guard for the CLI's tests and these.
#[path = "../../../ccdsim-cli/tests/common/scratch.rs"]
pub mod scratch;

use scratch::ScratchDir;

use ccdsim::record::RunWriter;
use ccdsim::{Scene, Simulation};
use ccdsim_viewer::{serve, KeyframeOptions, ServeOptions, StopHandle};
use std::io::{Read, Write};
use std::path::Path;

/// A fresh directory for one test's files, removed when it is dropped.
pub fn temp_dir(name: &str) -> ScratchDir {
    ScratchDir::new(&format!("viewer-{name}"))
}

/// Records `scene` run until `until` with the all-pairs finder to `path`; returns the events.
pub fn record<const D: usize>(scene: &Scene<D>, until: f64, path: &Path) -> u64 {
    let mut sim = Simulation::new(scene, "all-pairs").unwrap();
    let mut w = RunWriter::create(path, scene).unwrap();
    let n = sim.run_until_with(until, |c| w.write_event(c).unwrap());
    w.finish(until).unwrap();
    n
}

/// A viewer server answering on a thread of its own; dropping it stops the server and joins
/// the thread.
pub struct Running {
    /// The port it listens on at 127.0.0.1.
    pub port: u16,
    stop: StopHandle,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drop for Running {
    fn drop(&mut self) {
        self.stop.stop();
        if let Some(t) = self.thread.take() {
            t.join().unwrap();
        }
    }
}

/// Serves the run file `run` on 127.0.0.1 at a port the system picks, with keyframes per
/// `keyframes`, on a new thread.
pub fn start(run: &Path, keyframes: KeyframeOptions) -> Running {
    let options = ServeOptions {
        keyframes,
        ..ServeOptions::default()
    };
    let server = serve(run, 0, &options).unwrap();
    assert!(
        server.url().starts_with("http://127.0.0.1:"),
        "{}",
        server.url()
    );
    let port = server.port();
    assert_ne!(port, 0);
    let stop = server.stop_handle();
    let thread = Some(std::thread::spawn(move || server.run()));
    Running { port, stop, thread }
}

/// One HTTP answer.
pub struct Answer {
    pub status: u16,
    pub head: String,
    pub body: Vec<u8>,
}

/// GETs `path` from 127.0.0.1:`port` over a raw HTTP/1.0 connection.
pub fn get(port: u16, path: &str) -> Answer {
    let mut s = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(s, "GET {path} HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n").unwrap();
    let mut raw = Vec::new();
    s.read_to_end(&mut raw).unwrap();
    let split = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("HTTP head");
    let head = String::from_utf8(raw[..split].to_vec()).unwrap();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    Answer {
        status,
        head,
        body: raw[split + 4..].to_vec(),
    }
}

/// Little-endian `f64`s.
pub fn f64s(b: &[u8]) -> Vec<f64> {
    b.chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// Little-endian `f32`s.
pub fn f32s(b: &[u8]) -> Vec<f32> {
    b.chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect()
}
