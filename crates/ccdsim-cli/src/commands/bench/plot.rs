//! Log-log plots of running time against n, in the style of the thesis's Figure 5.1.

use anyhow::{anyhow, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One curve of measured times.
pub struct Series {
    /// Legend text.
    pub label: String,
    /// (n, seconds) points, increasing in n.
    pub points: Vec<(f64, f64)>,
    /// The thesis's own measurements (drawn dashed and paler).
    pub thesis: bool,
    /// Index into the palette: a thesis series takes the colour of the finder it measured.
    pub colour: usize,
}

/// A reference curve: its legend and its shape as a function of n.
type Reference = (&'static str, fn(f64) -> f64);

const COLOURS: [RGBColor; 6] = [
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x8c, 0x56, 0x4b),
];

/// Writes the plot to `path`, PNG or SVG by its extension.
///
/// Like Figure 5.1, an n² and an n·log n reference curve are drawn for comparison. Both start
/// from the fastest time measured here (the series that are not the thesis's) at the smallest
/// n plotted, so each measured curve's slope reads against theirs from a common origin.
pub fn plot_times(path: &Path, title: &str, series: &[Series]) -> Result<()> {
    let size = (1100, 750);
    match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => draw(
            SVGBackend::new(path, size).into_drawing_area(),
            title,
            series,
        ),
        Some("png") => draw(
            BitMapBackend::new(path, size).into_drawing_area(),
            title,
            series,
        ),
        _ => Err(anyhow!("{}: plots are .png or .svg", path.display())),
    }
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    series: &[Series],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plotting: {e:?}");
    root.fill(&WHITE).map_err(err)?;
    let all = series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in all.clone() {
        x0 = x0.min(x);
        x1 = x1.max(x);
        if y > 0.0 {
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 || y0 > y1 {
        return Err(anyhow!("nothing to plot: no cell completed"));
    }
    // The reference curves start from the fastest of our times at the smallest n (any of our
    // times at all if none was measured there).
    let ours = || {
        series
            .iter()
            .filter(|s| !s.thesis)
            .flat_map(|s| s.points.iter())
    };
    let fastest_at = |at: Option<f64>| {
        ours()
            .filter(|p| p.1 > 0.0 && at.is_none_or(|x| p.0 == x))
            .map(|p| p.1)
            .fold(f64::INFINITY, f64::min)
    };
    let first_x = ours().map(|p| p.0).fold(f64::INFINITY, f64::min);
    let (anchor_x, anchor_y) = match fastest_at(Some(first_x)) {
        y if y.is_finite() => (first_x, y),
        _ => (x0, fastest_at(None).min(y1)),
    };
    let references: [Reference; 2] = [
        ("n² (scaled)", |n| n * n),
        ("n log n (scaled)", |n| n * n.ln()),
    ];
    let ref_points: Vec<(String, Vec<(f64, f64)>)> = references
        .iter()
        .filter_map(|(label, f)| {
            // n log n is 0 at n = 1: no scale makes it pass through the anchor there.
            let k = anchor_y / f(anchor_x);
            if !(k.is_finite() && k > 0.0) {
                return None;
            }
            let mut xs = Vec::new();
            let mut n = x0;
            while n <= x1 * 1.0001 {
                xs.push(n);
                n *= 1.1;
            }
            xs.push(x1);
            // A log axis has no place for 0 (n log n at n = 1).
            let pts = xs
                .into_iter()
                .map(|n| (n, k * f(n)))
                .filter(|p| p.1 > 0.0)
                .collect();
            Some((label.to_string(), pts))
        })
        .collect();
    for (_, pts) in &ref_points {
        for &(_, y) in pts {
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(90)
        .build_cartesian_2d(
            (x0 / 1.3..x1 * 1.3).log_scale(),
            (y0 / 2.0..y1 * 2.0).log_scale(),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("number of bodies n")
        .y_desc("seconds per run (log scale)")
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .x_label_formatter(&|x| format!("{x:.0}"))
        .draw()
        .map_err(err)?;
    for (k, (label, pts)) in ref_points.iter().enumerate() {
        let style = if k == 0 {
            BLACK
        } else {
            RGBColor(0x70, 0x70, 0x70)
        };
        chart
            .draw_series(DashedLineSeries::new(
                pts.clone(),
                6,
                4,
                style.stroke_width(1),
            ))
            .map_err(err)?
            .label(label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
    }
    for s in series {
        let colour = COLOURS[s.colour % COLOURS.len()];
        let stroke = if s.thesis {
            colour.mix(0.5).stroke_width(2)
        } else {
            colour.stroke_width(2)
        };
        if s.thesis {
            chart
                .draw_series(DashedLineSeries::new(s.points.clone(), 3, 3, stroke))
                .map_err(err)?
                .label(s.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], stroke));
        } else {
            chart
                .draw_series(LineSeries::new(s.points.clone(), stroke))
                .map_err(err)?
                .label(s.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], stroke));
        }
        chart
            .draw_series(s.points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}
