//! Figures (SVG and PNG) drawn with `plotters` without system fonts: the DejaVu Sans font is
//! embedded and registered once under the family name `sans-serif`.

pub(crate) mod angle_panel;
pub(crate) mod cluster;
pub(crate) mod cushion;
pub(crate) mod paths;
pub(crate) mod rebound;
pub(crate) mod style;
pub(crate) mod sweep;
pub(crate) mod trace;
pub(crate) mod work_precision;

use crate::base::error::Error;
use crate::outputs::atomic_file::AtomicFile;
use plotters::coord::Shift;
use plotters::prelude::{BitMapBackend, DrawingArea, IntoDrawingArea, SVGBackend};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// The font family every figure uses.
pub const FONT: &str = "sans-serif";

/// Registers the embedded font with `plotters` (idempotent). Call before drawing text.
pub fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        use plotters::style::FontStyle;
        // The embedded bytes are a valid font; a failure here is a build defect.
        plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular())
            .unwrap_or_else(|_| panic!("embedded DejaVu Sans is not a valid font"));
        plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold())
            .unwrap_or_else(|_| panic!("embedded DejaVu Sans Bold is not a valid font"));
    });
}

/// The formats a figure is written in, told by its file name's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FigureFormat {
    /// Scalable vector graphics (`.svg`).
    Svg,
    /// A bitmap (`.png`).
    Png,
}

impl FigureFormat {
    /// The format of the figure file `path` given to the option `option` (e.g. `--plot`):
    /// `.svg` or `.png` (any case); any other name is refused naming the option, the file
    /// and the accepted extensions.
    pub(crate) fn of(option: &str, path: &Path) -> Result<Self, Error> {
        let ext = path.extension().and_then(|e| e.to_str());
        match ext.map(str::to_ascii_lowercase).as_deref() {
            Some("svg") => Ok(FigureFormat::Svg),
            Some("png") => Ok(FigureFormat::Png),
            _ => Err(Error::invalid(
                option,
                path.display(),
                "a file name ending in .svg or .png",
            )),
        }
    }
}

/// A figure of `dims` (px) written to `path` as SVG or PNG by its extension (checked by
/// [`FigureFormat::of`] for the option `option`), drawn by `draw_svg` or `draw_png` (the
/// same drawing on the two backends); the file is replaced only once complete.
pub(crate) fn write_figure(
    option: &str,
    path: &Path,
    dims: (u32, u32),
    draw_svg: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String>,
    draw_png: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<(), Error> {
    match FigureFormat::of(option, path)? {
        FigureFormat::Svg => write_svg(dims, path, draw_svg),
        FigureFormat::Png => write_png(dims, path, draw_png),
    }
}

/// A figure of `dims` (px) drawn by `draw_svg` as SVG to `svg` and by `draw_png` as PNG to
/// `png` (the same drawing on the two backends), each file replaced only once complete.
pub fn write_svg_and_png(
    dims: (u32, u32),
    svg: &Path,
    png: &Path,
    draw_svg: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String>,
    draw_png: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<(), Error> {
    write_svg(dims, svg, draw_svg)?;
    write_png(dims, png, draw_png)
}

/// The SVG drawn by `draw` written to `path` through an atomic file.
fn write_svg(
    dims: (u32, u32),
    path: &Path,
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<(), Error> {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, dims).into_drawing_area();
        draw(&root).map_err(|e| plot_error(path, e))?;
    }
    let mut file = AtomicFile::create(path)?;
    file.write_all(text.as_bytes())
        .map_err(|e| Error::io(path, e))?;
    file.commit()
}

/// The PNG drawn by `draw` written to `path`. The bitmap backend picks the format from the
/// extension: a temporary `.png` beside the target, renamed over it.
fn write_png(
    dims: (u32, u32),
    path: &Path,
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<(), Error> {
    // The checks of an atomic file (a directory, a missing or read-only folder) before
    // drawing; the file itself is dropped unused.
    drop(AtomicFile::create(path)?);
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "figure".into());
    let temp = dir.join(format!(".{stem}.{}.tmp.png", std::process::id()));
    let drawn = {
        let root = BitMapBackend::new(&temp, dims).into_drawing_area();
        draw(&root).map_err(|e| plot_error(path, e))
    };
    if let Err(e) = drawn {
        let _ = std::fs::remove_file(&temp);
        return Err(e);
    }
    std::fs::rename(&temp, path).map_err(|e| {
        let _ = std::fs::remove_file(&temp);
        Error::io(path, e)
    })
}

fn plot_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Plot {
        path: path.into(),
        message: format!("drawing the figure: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use plotters::prelude::*;

    /// A figure with text renders to SVG and PNG without fontconfig.
    #[test]
    fn renders_text_without_system_fonts() {
        super::register_fonts();
        let dir = std::env::temp_dir().join(format!("bc-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let png = dir.join("t.png");
        {
            let root = BitMapBackend::new(&png, (200, 100)).into_drawing_area();
            root.fill(&WHITE).unwrap();
            root.draw(&Text::new("S(t)", (10, 10), (super::FONT, 20).into_font()))
                .unwrap();
            root.present().unwrap();
        }
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (200, 100)).into_drawing_area();
            root.draw(&Text::new("theta", (10, 10), (super::FONT, 20).into_font()))
                .unwrap();
            root.present().unwrap();
        }
        assert!(svg.contains("theta"));
        assert!(std::fs::metadata(&png).unwrap().len() > 100);
        std::fs::remove_dir_all(&dir).ok();
    }

    /// The examples of the documentation of `FigureFormat::of`.
    #[test]
    fn figure_format_of_examples() {
        use super::FigureFormat;
        use std::path::Path;
        assert_eq!(
            FigureFormat::of("--plot", Path::new("a/top.PNG")).unwrap(),
            FigureFormat::Png
        );
        let e = FigureFormat::of("--plot", Path::new("p.pdf"))
            .unwrap_err()
            .to_string();
        assert_eq!(e, "--plot = p.pdf: a file name ending in .svg or .png");
    }
}
