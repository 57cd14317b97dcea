//! Writing one figure file: SVG or PNG by the file's extension, drawn on a
//! [`Figure`] and put in place atomically ([`crate::files::render_atomic`]).
//! Every picture of the crate is written here.

use super::canvas::{draw_err, Figure, FigureError, MAX_SIDE};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;
use std::sync::OnceLock;

/// The drawing area of a whole figure.
pub type Area<'a> = DrawingArea<Figure<'a>, Shift>;

/// Refuses a picture smaller than `least` or larger than [`MAX_SIDE`] a side.
pub fn check_size(size: (u32, u32), least: (u32, u32)) -> Result<(), FigureError> {
    if size.0 < least.0 || size.1 < least.1 {
        return Err(FigureError::TooSmall { size, least });
    }
    if size.0 > MAX_SIDE || size.1 > MAX_SIDE {
        return Err(FigureError::TooLarge(size.0, size.1));
    }
    Ok(())
}

static FONTS: OnceLock<bool> = OnceLock::new();

/// Registers the embedded DejaVu Sans (regular and bold) as `sans-serif`,
/// which plotters measures some text with. Runs once per process.
fn register_fonts() -> Result<(), FigureError> {
    let ok = *FONTS.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .is_ok()
            && plotters::style::register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold())
                .is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(FigureError::Font)
    }
}

/// Writes `path` (its parent folder created), a `size` picture drawn by
/// `draw`: SVG if the name ends in `.svg`, PNG if in `.png`.
pub fn write_figure(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&Area) -> Result<(), FigureError>,
) -> Result<(), FigureError> {
    check_size(size, (1, 1))?;
    let svg = match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => true,
        Some("png") => false,
        _ => return Err(FigureError::Format(path.to_path_buf())),
    };
    register_fonts()?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| FigureError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
    }
    crate::files::render_atomic(path, |tmp| {
        let fig = if svg {
            Figure::svg(tmp, size)
        } else {
            Figure::png(tmp, size)
        };
        let root = fig.into_drawing_area();
        draw(&root)?;
        root.present().map_err(draw_err)
    })
    .map_err(FigureError::Draw)
}

/// A picture drawn as the PNG file would hold it, as RGB bytes (3 a pixel,
/// row-major): what tests compare.
pub fn render_rgb(
    size: (u32, u32),
    draw: impl FnOnce(&Area) -> Result<(), FigureError>,
) -> Result<Vec<u8>, FigureError> {
    register_fonts()?;
    let mut buf = vec![0u8; 3 * (size.0 as usize) * (size.1 as usize)];
    {
        let root = Figure::rgb(&mut buf, size).into_drawing_area();
        draw(&root)?;
        root.present().map_err(draw_err)?;
    }
    Ok(buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The extension chooses the format; any other name is refused before
    /// anything is written.
    #[test]
    fn the_extension_chooses_the_format() {
        let dir = std::env::temp_dir().join(format!("detach-figure-{}", std::process::id()));
        let fill = |a: &Area| a.fill(&WHITE).map_err(draw_err);
        write_figure(&dir.join("a.svg"), (20, 10), fill).unwrap();
        write_figure(&dir.join("a.png"), (20, 10), fill).unwrap();
        let svg = std::fs::read(dir.join("a.svg")).unwrap();
        let png = std::fs::read(dir.join("a.png")).unwrap();
        assert!(
            svg.starts_with(b"<svg "),
            "{}",
            String::from_utf8_lossy(&svg)
        );
        assert!(png.starts_with(b"\x89PNG"));
        for bad in ["a.pdf", "a", "a.SVG"] {
            let e = write_figure(&dir.join(bad), (20, 10), fill).unwrap_err();
            assert!(matches!(e, FigureError::Format(_)), "{bad}: {e}");
            assert!(!dir.join(bad).exists());
        }
        let e = write_figure(&dir.join("b.png"), (MAX_SIDE + 1, 10), fill).unwrap_err();
        assert!(matches!(e, FigureError::TooLarge(..)), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
