//! Line charts for the experiments, written as SVG and PNG with plotters.
//!
//! Text needs no installed fonts: plotters' `ab_glyph` font backend is used
//! with DejaVu Sans registered from bytes (the `dejavu` crate ships the TTF
//! files), so PNGs render their labels on a fresh machine. The SVG holds
//! plain `<text>` elements (`font-family="sans-serif"`) that any viewer
//! draws with its own fonts.

use std::path::Path;
use std::sync::Once;

use anyhow::{anyhow, Context};
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use dymsum_io::atomic::AtomicFile;

use super::measure::Figures;

/// The font family name the charts use (registered from bytes).
const FONT: &str = "sans-serif";

/// Registers DejaVu Sans as `sans-serif` for plotters (once).
fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid TTF shipped by the `dejavu` crate.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
    });
}

/// How a series' points are marked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// Filled circles.
    Circle,
    /// Filled triangles.
    Triangle,
    /// Crosses.
    Cross,
    /// Hollow squares.
    Square,
}

/// One line of a chart.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Colour.
    pub color: RGBColor,
    /// Point marker.
    pub marker: Marker,
    /// Dashed line instead of solid.
    pub dashed: bool,
    /// `(x, y)` points, x increasing; non-finite or (on log axes)
    /// non-positive points are skipped.
    pub points: Vec<(f64, f64)>,
}

/// A chart: title, axis labels and scales, series.
#[derive(Clone, Debug)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// Logarithmic x axis.
    pub x_log: bool,
    /// Logarithmic y axis.
    pub y_log: bool,
    /// The lines.
    pub series: Vec<Series>,
}

/// A palette that stays readable in print.
pub const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

/// Reads one method's time out of a measurement's figures.
pub type MethodTime = fn(&Figures) -> f64;

/// How the rotation and size experiments draw each timed method: name,
/// marker, dashed line, and its time.
pub const METHODS: [(&str, Marker, bool, MethodTime); 3] = [
    ("DYMSUM", Marker::Circle, false, |f| f.dymsum),
    ("walk", Marker::Triangle, true, |f| f.walk),
    ("brute", Marker::Cross, true, |f| f.brute),
];

/// One series per method of [`METHODS`] named in `wanted`, in that order,
/// labelled `"{prefix} {method}"` and drawn in `color`; `points` gives a
/// method's points.
pub fn method_series(
    prefix: &str,
    color: RGBColor,
    wanted: &[&str],
    points: impl Fn(MethodTime) -> Vec<(f64, f64)>,
) -> Vec<Series> {
    METHODS
        .iter()
        .filter(|(method, ..)| wanted.contains(method))
        .map(|&(method, marker, dashed, time)| Series {
            label: format!("{prefix} {method}"),
            color,
            marker,
            dashed,
            points: points(time),
        })
        .collect()
}

/// Chart size in pixels.
pub const SIZE: (u32, u32) = (1000, 600);

/// Writes the chart as an SVG file and a PNG file.
///
/// # Errors
/// Either file cannot be created, drawn or committed (naming the file); an
/// earlier chart at either path is kept.
pub fn write_chart(chart: &Chart, svg: &Path, png: &Path) -> anyhow::Result<()> {
    register_fonts();
    // Drawn under temporary names and renamed into place: a failure never
    // leaves a truncated chart or destroys an earlier one.
    {
        let file = AtomicFile::create(svg)?;
        {
            let root = SVGBackend::new(file.temp_path(), SIZE).into_drawing_area();
            draw(&root, chart).with_context(|| format!("drawing {}", svg.display()))?;
            root.present()
                .map_err(|e| anyhow!("{}: {e}", svg.display()))?;
        }
        file.commit()?;
    }
    {
        let file = AtomicFile::create(png)?;
        {
            let root = BitMapBackend::new(file.temp_path(), SIZE).into_drawing_area();
            draw(&root, chart).with_context(|| format!("drawing {}", png.display()))?;
            root.present()
                .map_err(|e| anyhow!("{}: {e}", png.display()))?;
        }
        file.commit()?;
    }
    Ok(())
}

/// The points of a series that can be drawn on the chart's axes.
fn drawable(chart: &Chart, s: &Series) -> Vec<(f64, f64)> {
    s.points
        .iter()
        .copied()
        .filter(|&(x, y)| {
            x.is_finite() && y.is_finite() && (!chart.x_log || x > 0.0) && (!chart.y_log || y > 0.0)
        })
        .collect()
}

/// Axis range covering `v` with a margin (multiplicative on log axes).
fn range(v: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    if !lo.is_finite() || !hi.is_finite() {
        return if log { (1.0, 10.0) } else { (0.0, 1.0) };
    }
    if log {
        lo /= 1.5;
        hi *= 1.5;
    } else {
        let pad = ((hi - lo) * 0.05).max(hi.abs() * 0.05).max(1e-9);
        lo = if lo >= 0.0 { 0.0 } else { lo - pad };
        hi += pad;
    }
    (lo, hi)
}

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, chart: &Chart) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let pts: Vec<Vec<(f64, f64)>> = chart.series.iter().map(|s| drawable(chart, s)).collect();
    let (x0, x1) = range(pts.iter().flatten().map(|p| p.0), chart.x_log);
    let (y0, y1) = range(pts.iter().flatten().map(|p| p.1), chart.y_log);
    match (chart.x_log, chart.y_log) {
        (true, true) => draw_in(
            root,
            chart,
            &pts,
            (x0..x1).log_scale(),
            (y0..y1).log_scale(),
        ),
        (true, false) => draw_in(root, chart, &pts, (x0..x1).log_scale(), y0..y1),
        (false, true) => draw_in(root, chart, &pts, x0..x1, (y0..y1).log_scale()),
        (false, false) => draw_in(root, chart, &pts, x0..x1, y0..y1),
    }
}

fn draw_in<DB, XR, YR>(
    root: &DrawingArea<DB, Shift>,
    chart: &Chart,
    pts: &[Vec<(f64, f64)>],
    xr: XR,
    yr: YR,
) -> anyhow::Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    XR: AsRangedCoord<Value = f64>,
    YR: AsRangedCoord<Value = f64>,
    XR::CoordDescType: ValueFormatter<f64>,
    YR::CoordDescType: ValueFormatter<f64>,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e}");
    let (w, _) = root.dim_in_pixel();
    let (plot_area, legend_area) = root.split_horizontally(w.saturating_sub(LEGEND_WIDTH));
    draw_legend(&legend_area, chart)?;
    let mut cc = ChartBuilder::on(&plot_area)
        .caption(&chart.title, (FONT, 22).into_font())
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d(xr, yr)
        .map_err(err)?;
    cc.configure_mesh()
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .label_style((FONT, 14).into_font())
        .axis_desc_style((FONT, 16).into_font())
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()
        .map_err(err)?;
    for (s, p) in chart.series.iter().zip(pts) {
        draw_one_series(&mut cc, s, p)?;
    }
    Ok(())
}

/// One series: its line (solid or dashed) and its markers.
fn draw_one_series<DB, X, Y>(
    cc: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    s: &Series,
    p: &[(f64, f64)],
) -> anyhow::Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e}");
    let color = s.color;
    let line = ShapeStyle::from(&color).stroke_width(2);
    if s.dashed {
        cc.draw_series(DashedLineSeries::new(p.iter().copied(), 8, 5, line))
            .map_err(err)?;
    } else {
        cc.draw_series(LineSeries::new(p.iter().copied(), line))
            .map_err(err)?;
    }
    match s.marker {
        Marker::Circle => cc.draw_series(
            p.iter()
                .map(|&c| Circle::new(c, 4, ShapeStyle::from(&color).filled())),
        ),
        Marker::Triangle => cc.draw_series(
            p.iter()
                .map(|&c| TriangleMarker::new(c, 5, ShapeStyle::from(&color).filled())),
        ),
        Marker::Cross => cc.draw_series(
            p.iter()
                .map(|&c| Cross::new(c, 4, ShapeStyle::from(&color).stroke_width(2))),
        ),
        Marker::Square => cc.draw_series(p.iter().map(|&(x, y)| {
            EmptyElement::at((x, y))
                + Rectangle::new([(-4, -4), (4, 4)], ShapeStyle::from(&color).stroke_width(2))
        })),
    }
    .map_err(err)?;
    Ok(())
}

/// Width of the legend column on the right, in pixels.
const LEGEND_WIDTH: u32 = 230;

/// The legend, in its own column right of the plot (never over the data).
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e}");
    let style = TextStyle::from((FONT, 14).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (i, s) in chart.series.iter().enumerate() {
        let y = 70 + 24 * i as i32;
        let line = ShapeStyle::from(&s.color).stroke_width(2);
        if s.dashed {
            area.draw(&PathElement::new(vec![(6, y), (14, y)], line))
                .map_err(err)?;
            area.draw(&PathElement::new(vec![(20, y), (28, y)], line))
                .map_err(err)?;
            area.draw(&PathElement::new(vec![(34, y), (40, y)], line))
                .map_err(err)?;
        } else {
            area.draw(&PathElement::new(vec![(6, y), (40, y)], line))
                .map_err(err)?;
        }
        area.draw(&marker_element(s.marker, s.color, (23, y)))
            .map_err(err)?;
        area.draw(&Text::new(s.label.as_str(), (50, y), style.clone()))
            .map_err(err)?;
    }
    Ok(())
}

/// An axis tick label: `10`, `1,000`, `0.5`, `2.5e-3`.
fn tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".to_string()
    } else if !(1e-3..1e7).contains(&a) {
        format!("{v:.1e}")
    } else if (v - v.round()).abs() < 1e-9 * a.max(1.0) {
        let n = v.round() as i64;
        let digits = n.unsigned_abs().to_string();
        let grouped: Vec<String> = digits
            .as_bytes()
            .rchunks(3)
            .rev()
            .map(|c| String::from_utf8_lossy(c).into_owned())
            .collect();
        let grouped = grouped.join(",");
        if n < 0 {
            format!("-{grouped}")
        } else {
            grouped
        }
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// A marker in backend pixel coordinates (for the legend).
fn marker_element<DB: DrawingBackend>(
    marker: Marker,
    color: RGBColor,
    at: (i32, i32),
) -> DynElement<'static, DB, (i32, i32)> {
    match marker {
        Marker::Circle => Circle::new(at, 4, ShapeStyle::from(&color).filled()).into_dyn(),
        Marker::Triangle => {
            TriangleMarker::new(at, 5, ShapeStyle::from(&color).filled()).into_dyn()
        }
        Marker::Cross => Cross::new(at, 4, ShapeStyle::from(&color).stroke_width(2)).into_dyn(),
        Marker::Square => Rectangle::new(
            [(at.0 - 4, at.1 - 4), (at.0 + 4, at.1 + 4)],
            ShapeStyle::from(&color).stroke_width(2),
        )
        .into_dyn(),
    }
}
