//! The HTTP server: one embedded page and a small API, on 127.0.0.1 only.
//!
//! tiny_http is used because the viewer needs a few GET routes served to one local browser:
//! it is a small synchronous server with four small dependencies and no async runtime, so
//! the binary stays lean and requests are answered one at a time against one open run file.

use crate::assets;
use crate::error::ViewerError;
use crate::keyframes::KeyframeOptions;
use crate::playback::{AnyPlayback, Playback};
use crate::pool::PoolPlayback;
use crate::wire;
use ccdsim::record::{run_file_version, VERSION_POOL};
use ccdsim::FinderOptions;
use std::path::Path;
use std::sync::Arc;
use tiny_http::{Header, Method, Request, Response};

/// Most events one `/api/events` request returns.
pub const MAX_EVENT_WINDOW: u64 = 1 << 16;

/// Options of [`serve`].
#[derive(Clone, Debug, PartialEq)]
pub struct ServeOptions {
    /// Finder whose boxes the page draws; `bvh` by default.
    pub finder: String,
    /// Options of that finder.
    pub finder_options: FinderOptions,
    /// Keyframe density.
    pub keyframes: KeyframeOptions,
}

impl Default for ServeOptions {
    fn default() -> Self {
        ServeOptions {
            finder: "bvh".to_string(),
            finder_options: FinderOptions::default(),
            keyframes: KeyframeOptions::default(),
        }
    }
}

/// A viewer bound to its port, ready to [`ViewerServer::run`].
pub struct ViewerServer {
    http: Arc<tiny_http::Server>,
    playback: Served,
    options: ServeOptions,
    port: u16,
}

/// What a viewer serves: a scene's run (the run page) or a pool shot (the pool page).
enum Served {
    Run(Box<AnyPlayback>),
    Pool {
        page: Box<PoolPlayback>,
        /// The pool page's JSON, built on its first request.
        json: Option<Vec<u8>>,
    },
}

/// Stops a running [`ViewerServer`] from another thread.
#[derive(Clone)]
pub struct StopHandle(Arc<tiny_http::Server>);

impl StopHandle {
    /// Makes [`ViewerServer::run`] return after the request it is answering, if any.
    pub fn stop(&self) {
        self.0.unblock();
    }
}

/// Binds `127.0.0.1:port` (0 picks any free port), then opens the run at `run_path` (one
/// pass over the file to build its keyframe index). Call [`ViewerServer::run`] to answer
/// requests. Binding first means a taken port is reported before a long indexing pass.
pub fn serve(
    run_path: &Path,
    port: u16,
    options: &ServeOptions,
) -> Result<ViewerServer, ViewerError> {
    let addr = format!("127.0.0.1:{port}");
    let http = tiny_http::Server::http(&addr).map_err(|e| ViewerError::Bind {
        addr: addr.clone(),
        why: e.to_string(),
    })?;
    let port = http.server_addr().to_ip().map_or(port, |a| a.port());
    let playback = if run_file_version(run_path)? == VERSION_POOL {
        Served::Pool {
            page: Box::new(PoolPlayback::open(run_path)?),
            json: None,
        }
    } else {
        Served::Run(Box::new(AnyPlayback::open(run_path, &options.keyframes)?))
    };
    Ok(ViewerServer {
        http: Arc::new(http),
        playback,
        options: options.clone(),
        port,
    })
}

impl ViewerServer {
    /// The port bound.
    #[must_use]
    pub fn port(&self) -> u16 {
        self.port
    }

    /// The page's address, `http://127.0.0.1:PORT/`.
    #[must_use]
    pub fn url(&self) -> String {
        format!("http://127.0.0.1:{}/", self.port)
    }

    /// A handle that stops [`ViewerServer::run`].
    #[must_use]
    pub fn stop_handle(&self) -> StopHandle {
        StopHandle(Arc::clone(&self.http))
    }

    /// Answers requests one at a time until stopped.
    pub fn run(mut self) {
        let http = Arc::clone(&self.http);
        for req in http.incoming_requests() {
            let answer = self.answer(&req);
            // A browser that went away mid-answer is not the server's problem.
            let _ = req.respond(answer);
        }
    }

    fn answer(&mut self, req: &Request) -> Response<std::io::Cursor<Vec<u8>>> {
        if *req.method() != Method::Get {
            return error(405, "only GET is served");
        }
        let (path, query) = req.url().split_once('?').unwrap_or((req.url(), ""));
        if let Served::Pool { page, json } = &mut self.playback {
            return pool_answer(page, json, path);
        }
        if let Some(a) = assets::find(path) {
            return Response::from_data(a.body.to_vec())
                .with_header(header("Content-Type", a.content_type));
        }
        let Some(route) = path.strip_prefix("/api/") else {
            return error(404, &format!("no such page: {path}"));
        };
        let q = Query::parse(query);
        let Served::Run(playback) = &mut self.playback else {
            unreachable!("a pool shot is answered above")
        };
        let result = match playback.as_mut() {
            AnyPlayback::D2(p) => api(p, &self.options, route, &q),
            AnyPlayback::D3(p) => api(p, &self.options, route, &q),
        };
        match result {
            Ok(Some(Body::Json(v))) => Response::from_data(v.to_string().into_bytes())
                .with_header(header("Content-Type", "application/json"))
                .with_header(header("Cache-Control", "no-store")),
            Ok(Some(Body::Binary(b))) => Response::from_data(b)
                .with_header(header("Content-Type", "application/octet-stream"))
                .with_header(header("Cache-Control", "no-store")),
            Ok(None) => error(404, &format!("no such API: /api/{route}")),
            Err(e) => error(400, &e.to_string()),
        }
    }
}

/// The pool page: `/` is `pool.html`, `/api/pool` its JSON ([`PoolPlayback::page_json`]).
fn pool_answer(
    page: &PoolPlayback,
    json: &mut Option<Vec<u8>>,
    path: &str,
) -> Response<std::io::Cursor<Vec<u8>>> {
    if path == "/api/pool" {
        let body = json.get_or_insert_with(|| page.page_json().to_string().into_bytes());
        return Response::from_data(body.clone())
            .with_header(header("Content-Type", "application/json"))
            .with_header(header("Cache-Control", "no-store"));
    }
    let path = if path == "/" { "/pool.html" } else { path };
    match assets::find(path) {
        Some(a) => {
            Response::from_data(a.body.to_vec()).with_header(header("Content-Type", a.content_type))
        }
        None => error(
            404,
            &format!("no such page: {path} (a pool shot is served at / and /api/pool)"),
        ),
    }
}

enum Body {
    Json(serde_json::Value),
    Binary(Vec<u8>),
}

fn api<const D: usize>(
    p: &mut Playback<D>,
    options: &ServeOptions,
    route: &str,
    q: &Query,
) -> Result<Option<Body>, ViewerError> {
    Ok(Some(match route {
        "meta" => Body::Json(wire::meta_json(p, &options.finder)),
        "bodies" => Body::Binary(wire::encode_bodies(p)),
        "state" => {
            let snap = match (q.f64("t")?, q.u64("k")?) {
                (Some(t), None) => p.snapshot_at(t)?,
                (None, Some(k)) => p.snapshot_after(k)?,
                _ => {
                    return Err(ViewerError::param(
                        "state",
                        "give exactly one of t (seconds) or k (events)",
                    ))
                }
            };
            Body::Binary(wire::encode_snapshot(&snap))
        }
        "events" => {
            let from = q.u64("from")?.unwrap_or(0);
            let count = q.u64("count")?.unwrap_or(4096).min(MAX_EVENT_WINDOW);
            let rests = p.has_rests();
            Body::Binary(wire::encode_events(&p.events_window(from, count)?, rests))
        }
        "step" => {
            let t = q
                .f64("t")?
                .ok_or_else(|| ViewerError::param("t", "missing"))?;
            let to = match q.get("dir") {
                Some("next") => p.next_event_time(t)?,
                Some("prev") => p.prev_event_time(t)?,
                _ => return Err(ViewerError::param("dir", "must be next or prev")),
            };
            Body::Json(serde_json::json!({ "time": to }))
        }
        "boxes" => {
            let t = q
                .f64("t")?
                .ok_or_else(|| ViewerError::param("t", "missing"))?;
            let finder = q.get("finder").unwrap_or(&options.finder);
            let snap = p.snapshot_at(t)?;
            Body::Binary(wire::encode_boxes(&p.finder_boxes(
                &snap,
                finder,
                &options.finder_options,
            )?))
        }
        _ => return Ok(None),
    }))
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("static ASCII header")
}

fn error(code: u16, message: &str) -> Response<std::io::Cursor<Vec<u8>>> {
    let body = serde_json::json!({ "error": message }).to_string();
    Response::from_data(body.into_bytes())
        .with_status_code(code)
        .with_header(header("Content-Type", "application/json"))
}

/// The parameters of a query string (`a=1&b=2`; values are numbers or plain names, so no
/// percent-decoding is needed beyond refusing what is not plain).
struct Query<'a>(Vec<(&'a str, &'a str)>);

impl<'a> Query<'a> {
    fn parse(q: &'a str) -> Self {
        Query(
            q.split('&')
                .filter(|s| !s.is_empty())
                .map(|kv| kv.split_once('=').unwrap_or((kv, "")))
                .collect(),
        )
    }

    fn get(&self, name: &str) -> Option<&'a str> {
        self.0
            .iter()
            .rev()
            .find(|(k, _)| *k == name)
            .map(|(_, v)| *v)
    }

    fn f64(&self, name: &str) -> Result<Option<f64>, ViewerError> {
        self.get(name)
            .map(|v| match v.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(ViewerError::param(
                    name,
                    format!("`{v}` is not a finite number"),
                )),
            })
            .transpose()
    }

    fn u64(&self, name: &str) -> Result<Option<u64>, ViewerError> {
        self.get(name)
            .map(|v| {
                v.parse::<u64>()
                    .map_err(|_| ViewerError::param(name, format!("`{v}` is not a whole number")))
            })
            .transpose()
    }
}
