//! Figures (SVG and PNG) drawn with `plotters` without system fonts: the DejaVu Sans font is
//! embedded and registered once under the family name `sans-serif`.

pub mod work_precision;

use std::sync::Once;

pub mod paths;

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
}
