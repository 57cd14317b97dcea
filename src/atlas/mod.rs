//! Drawing pavings and phase portraits (SVG and PNG).
use crate::pave::Paving;
use crate::scene::{Scene, Variant};
use std::path::Path;

pub struct AtlasStyle {
    pub width: u32,
    pub height: u32,
}
impl Default for AtlasStyle {
    fn default() -> Self {
        AtlasStyle {
            width: 1200,
            height: 800,
        }
    }
}
pub struct PictureInfo<'a> {
    pub scene: &'a Scene,
    pub variant: Variant,
    pub params: Vec<(&'static str, String)>,
    pub complete: bool,
}
pub fn plot_area_pixels(style: &AtlasStyle) -> (u32, u32) {
    (style.width - 200, style.height - 150)
}
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct AtlasError(String);
pub fn draw_atlas(
    _: &Paving,
    _: &PictureInfo,
    _: &AtlasStyle,
    _: &Path,
    _: &Path,
) -> Result<(), AtlasError> {
    Ok(())
}
