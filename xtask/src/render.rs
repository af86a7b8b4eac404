//! SVG to PNG in pure Rust (resvg), with the embedded DejaVu font, so that every figure
//! can be looked at as a reader sees it and checked by a test.

use std::path::Path;

use anyhow::{Context, Result, bail, ensure};
use resvg::{tiny_skia, usvg};

/// The largest side, in pixels, a figure may have before it is called unreadable at a
/// page's width (a page at 300 dpi is about 2500 px wide; our figures are drawn at
/// 96 dpi, so 2000 px is already twice a page).
pub const MAX_SIDE: f32 = 2000.0;

fn options() -> usvg::Options<'static> {
    let mut opt = usvg::Options {
        font_family: "DejaVu Sans".to_string(),
        ..usvg::Options::default()
    };
    let db = opt.fontdb_mut();
    db.load_font_data(dejavu::sans::regular().to_vec());
    db.load_font_data(dejavu::sans::bold().to_vec());
    db.set_sans_serif_family("DejaVu Sans");
    opt
}

/// Parse an SVG document and check that it is well formed and of a sane size: both sides
/// positive and at most [`MAX_SIDE`]. Returns its size in pixels.
pub fn check(svg: &str, what: &str) -> Result<(f32, f32)> {
    let tree = usvg::Tree::from_str(svg, &options())
        .with_context(|| format!("{what} is not a well-formed SVG document"))?;
    let size = tree.size();
    let (w, h) = (size.width(), size.height());
    ensure!(
        w > 0.0 && h > 0.0 && w <= MAX_SIDE && h <= MAX_SIDE,
        "{what} is {w:.0} by {h:.0} px: each side must be in 1..={MAX_SIDE}"
    );
    Ok((w, h))
}

/// The most pixels a rendered PNG may have (100 megapixels, 400 MB of pixmap): a larger
/// `--scale` is refused with the size it would make, before anything is allocated.
pub const MAX_PIXELS: f64 = 100e6;

/// The size in pixels of `width` by `height` scaled by `scale`, refused beyond
/// [`MAX_PIXELS`] (computed in floating point, so no size overflows).
fn scaled_size(width: u32, height: u32, scale: f32, what: &str) -> Result<(f64, f64)> {
    let (w, h) = (
        (f64::from(width) * f64::from(scale)).ceil(),
        (f64::from(height) * f64::from(scale)).ceil(),
    );
    let pixels = w * h;
    ensure!(
        pixels <= MAX_PIXELS,
        "{what}: --scale {scale} would make a {w:.0} by {h:.0} px image ({pixels:.2e} pixels, \
         {:.2e} bytes); at most {MAX_PIXELS:.0e} pixels may be rendered",
        pixels * 4.0
    );
    Ok((w, h))
}

/// Render an SVG document to PNG bytes at `scale` times its size.
pub fn png(svg: &str, scale: f32, what: &str) -> Result<Vec<u8>> {
    let tree = usvg::Tree::from_str(svg, &options())
        .with_context(|| format!("{what} is not a well-formed SVG document"))?;
    let int_size = tree.size().to_int_size();
    scaled_size(int_size.width(), int_size.height(), scale, what)?;
    let size = int_size.scale_by(scale);
    let Some(size) = size else {
        bail!("{what}: cannot scale by {scale}");
    };
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .with_context(|| format!("{what}: empty or too large to render"))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .with_context(|| format!("{what}: cannot encode PNG"))
}

/// The largest SVG `png` reads (16 MiB; the project's figures are under 1 MiB).
pub const MAX_SVG_BYTES: u64 = 16 << 20;

/// Read an SVG file: a regular file of at most [`MAX_SVG_BYTES`], as UTF-8 text.
fn read_svg(f: &Path) -> Result<String> {
    crate::files::read_text(f, MAX_SVG_BYTES, "an SVG file")
}

/// `cargo xtask png FILE.svg...`: write `FILE.png` beside each.
pub fn run(files: &[std::path::PathBuf], scale: f32) -> Result<()> {
    for f in files {
        let svg = read_svg(f)?;
        let what = f.display().to_string();
        check(&svg, &what)?;
        let out = f.with_extension("png");
        crate::files::write_atomic(&out, png(&svg, scale, &what)?)
            .with_context(|| format!("cannot write {}", out.display()))?;
        crate::emit(&format!("{}\n", Path::new(&out).display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn only_regular_svg_files_of_a_bounded_size_are_read() {
        let dir = std::env::temp_dir().join(format!("xtask-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let err = format!("{:#}", super::read_svg(&dir).unwrap_err());
        assert!(err.contains("not a regular file"), "{err}");
        let big = dir.join("big.svg");
        let file = std::fs::File::create(&big).unwrap();
        file.set_len(super::MAX_SVG_BYTES + 1).unwrap();
        let err = format!("{:#}", super::read_svg(&big).unwrap_err());
        assert!(err.contains("longer than"), "{err}");
        let bad = dir.join("bad.svg");
        std::fs::write(&bad, [0xff, 0xfe, b'<']).unwrap();
        let err = format!("{:#}", super::read_svg(&bad).unwrap_err());
        assert!(err.contains("not UTF-8"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    use super::*;

    const SQUARE: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300"><rect width="10" height="10"/></svg>"#;

    #[test]
    fn a_scale_past_the_pixel_cap_is_refused_with_the_estimate() {
        let err = png(SQUARE, 1e6, "f.svg").unwrap_err().to_string();
        assert!(err.contains("--scale 1000000"), "{err}");
        assert!(err.contains("400000000 by 300000000 px"), "{err}");
        assert!(err.contains("1.20e17 pixels"), "{err}");
        assert!(err.contains("at most 1e8 pixels"), "{err}");
        // The largest allowed size is checked without rendering; one step past it is refused.
        assert!(scaled_size(10_000, 10_000, 1.0, "f").is_ok());
        assert!(scaled_size(10_000, 10_001, 1.0, "f").is_err());
        assert!(scaled_size(u32::MAX, u32::MAX, f32::MAX, "f").is_err());
        // An ordinary scale still renders.
        let bytes = png(SQUARE, 2.0, "f.svg").unwrap();
        assert!(bytes.starts_with(b"\x89PNG"));
    }
}
