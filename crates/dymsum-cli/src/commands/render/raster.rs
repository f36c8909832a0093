//! The scene rasterised to PNG: our own scanline fill of convex polygons with
//! `SS × SS` supersampling, in horizontal bands (memory bounded by the band,
//! not the picture), encoded by the pure-Rust `png` crate. Pure `f64`
//! arithmetic, so the pixels (and the file) are the same on every run.

use anyhow::Context;

use super::scene::{Scene, BACKGROUND_RGB, CHANGED_EDGE_RGB, EDGE_RGB};

/// Samples per pixel along each axis.
const SS: usize = 4;
/// Output rows per band.
const BAND: usize = 32;

/// One convex polygon to fill, with its bounding rows (pixels).
struct Prim {
    points: Vec<[f64; 2]>,
    rgb: [u8; 3],
    y_min: f64,
    y_max: f64,
}

impl Prim {
    fn new(points: Vec<[f64; 2]>, rgb: [u8; 3]) -> Option<Prim> {
        if points.len() < 3 {
            return None;
        }
        let y_min = points.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        let y_max = points
            .iter()
            .map(|p| p[1])
            .fold(f64::NEG_INFINITY, f64::max);
        Some(Prim {
            points,
            rgb,
            y_min,
            y_max,
        })
    }
}

/// The outline of a polygon as one quad per side (square caps cover the
/// joins of thin lines).
fn outline(points: &[[f64; 2]], width: f64, rgb: [u8; 3], out: &mut Vec<Prim>) {
    let h = 0.5 * width;
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = (dx * dx + dy * dy).sqrt();
        if len == 0.0 || !len.is_finite() {
            continue;
        }
        let (ux, uy) = (dx / len * h, dy / len * h);
        let (nx, ny) = (-uy, ux);
        let quad = vec![
            [a[0] - ux + nx, a[1] - uy + ny],
            [b[0] + ux + nx, b[1] + uy + ny],
            [b[0] + ux - nx, b[1] + uy - ny],
            [a[0] - ux - nx, a[1] - uy - ny],
        ];
        out.extend(Prim::new(quad, rgb));
    }
}

/// The primitives in painter's order (as in the SVG).
fn primitives(scene: &Scene) -> Vec<Prim> {
    let mut out = Vec::new();
    for f in &scene.faces {
        out.extend(Prim::new(f.points.clone(), f.fill));
    }
    for f in &scene.changed {
        out.extend(Prim::new(f.points.clone(), f.fill));
        outline(
            &f.points,
            scene.changed_edge_width,
            CHANGED_EDGE_RGB,
            &mut out,
        );
    }
    for f in &scene.faces {
        outline(&f.points, scene.edge_width, EDGE_RGB, &mut out);
    }
    out
}

/// Fills the samples of one band (`rows` sample rows starting at sample row
/// `row0`, `width` samples wide) covered by the convex polygon `prim`. A
/// sample at index `(i, j)` sits at pixel coordinates
/// `((i + 0.5) / SS, (j + 0.5) / SS)`.
fn fill(buf: &mut [[u8; 3]], width: usize, row0: usize, rows: usize, prim: &Prim) {
    let s = SS as f64;
    let j_lo = ((prim.y_min * s - 0.5).ceil().max(row0 as f64)) as usize;
    let j_hi_f = (prim.y_max * s - 0.5).floor();
    if j_hi_f < row0 as f64 {
        return;
    }
    let j_hi = (j_hi_f as usize).min(row0 + rows - 1);
    let n = prim.points.len();
    for j in j_lo..=j_hi {
        let y = (j as f64 + 0.5) / s;
        let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..n {
            let a = prim.points[k];
            let b = prim.points[(k + 1) % n];
            if (a[1] <= y && y < b[1]) || (b[1] <= y && y < a[1]) {
                let x = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                x0 = x0.min(x);
                x1 = x1.max(x);
            }
        }
        if x0 >= x1 {
            continue;
        }
        let i0 = (x0 * s - 0.5).ceil().clamp(0.0, width as f64) as usize;
        let i1 = (x1 * s - 0.5).ceil().clamp(0.0, width as f64) as usize;
        let row = &mut buf[(j - row0) * width..(j - row0 + 1) * width];
        for px in &mut row[i0..i1] {
            *px = prim.rgb;
        }
    }
}

/// The scene's pixels, row-major RGB.
pub fn rasterize(scene: &Scene) -> Vec<u8> {
    let size = scene.size as usize;
    let prims = primitives(scene);
    let width = size * SS;
    let mut pixels = Vec::with_capacity(size * size * 3);
    let mut buf = vec![BACKGROUND_RGB; width * BAND * SS];
    for y0 in (0..size).step_by(BAND) {
        let band = BAND.min(size - y0);
        let rows = band * SS;
        buf[..width * rows].fill(BACKGROUND_RGB);
        let (top, bottom) = (y0 as f64, (y0 + band) as f64);
        for prim in &prims {
            if prim.y_max >= top && prim.y_min <= bottom {
                fill(&mut buf, width, y0 * SS, rows, prim);
            }
        }
        for r in 0..band {
            for x in 0..size {
                let mut acc = [0u32; 3];
                for sj in 0..SS {
                    let base = (r * SS + sj) * width + x * SS;
                    for c in &buf[base..base + SS] {
                        for k in 0..3 {
                            acc[k] += c[k] as u32;
                        }
                    }
                }
                let n = (SS * SS) as u32;
                pixels.extend(acc.map(|a| ((a + n / 2) / n) as u8));
            }
        }
    }
    pixels
}

/// The scene as PNG bytes (8-bit RGB, no metadata chunks).
pub fn to_png(scene: &Scene) -> anyhow::Result<Vec<u8>> {
    let pixels = rasterize(scene);
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, scene.size, scene.size);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Best);
        let mut w = enc.write_header().context("encoding the PNG")?;
        w.write_image_data(&pixels).context("encoding the PNG")?;
        w.finish().context("encoding the PNG")?;
    }
    Ok(bytes)
}
