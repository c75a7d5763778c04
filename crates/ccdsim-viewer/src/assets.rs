//! The page's static files, embedded in the binary so the viewer needs no network.

/// One embedded file.
pub struct Asset {
    /// URL path, e.g. `/viewer.js`.
    pub path: &'static str,
    /// MIME type.
    pub content_type: &'static str,
    /// The bytes.
    pub body: &'static [u8],
}

/// Every file the pages load; `/` serves `index.html` (`pool.html` for a pool shot).
pub const ASSETS: &[Asset] = &[
    Asset {
        path: "/index.html",
        content_type: "text/html; charset=utf-8",
        body: include_bytes!("../assets/index.html"),
    },
    Asset {
        path: "/viewer.css",
        content_type: "text/css; charset=utf-8",
        body: include_bytes!("../assets/viewer.css"),
    },
    Asset {
        path: "/viewer.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_bytes!("../assets/viewer.js"),
    },
    Asset {
        path: "/pool.html",
        content_type: "text/html; charset=utf-8",
        body: include_bytes!("../assets/pool.html"),
    },
    Asset {
        path: "/pool.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_bytes!("../assets/pool.js"),
    },
    Asset {
        path: "/raster.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_bytes!("../assets/raster.js"),
    },
];

/// The asset served at `path`.
#[must_use]
pub fn find(path: &str) -> Option<&'static Asset> {
    let path = if path == "/" { "/index.html" } else { path };
    ASSETS.iter().find(|a| a.path == path)
}
