//! A scene as a family over parameter boxes: the scene rebuilt with the
//! parameters that vary enclosed as intervals, the others as given.

use super::model::ParamAxis;
use crate::number::param::{Param, ParamSet};
use crate::scene::{FileScene, Scene, SceneId, SceneText, Variant};
use inari::Interval;

/// Where the scene comes from: one of the paper's, or a scene file's text.
#[derive(Clone, Debug)]
pub enum Source {
    Paper(SceneId),
    File(SceneText),
}

impl Source {
    /// A scene by name (the paper's or a shipped file), as `--scene` takes it.
    pub fn by_name(name: &str) -> Result<Source, String> {
        if let Ok(id) = name.parse::<SceneId>() {
            return Ok(Source::Paper(id));
        }
        SceneText::shipped(name).map(Source::File).ok_or_else(|| {
            format!(
                "unknown scene `{name}` (known: {}, {})",
                SceneId::ALL.map(|i| i.name()).join(", "),
                crate::scene::file::SHIPPED.map(|s| s.0).join(", ")
            )
        })
    }

    /// The scene with `name=value` parameter overrides.
    pub fn scene(
        &self,
        overrides: &[(String, String)],
    ) -> Result<(Scene, ParamSet), crate::scene::SceneFileError> {
        match self {
            Source::Paper(id) => Scene::build(*id, overrides),
            Source::File(text) => {
                let f = text.compile(overrides)?;
                let params = f.params.clone();
                Ok((Scene::File(Box::new(f)), params))
            }
        }
    }
}

/// A scene whose parameters `axes` vary over a box.
#[derive(Clone, Debug)]
pub struct Family {
    source: Source,
    pub variant: Variant,
    overrides: Vec<(String, String)>,
    pub axes: Vec<ParamAxis>,
    /// The root box: per axis, the outer ends of the ends' enclosures.
    pub root: Vec<[f64; 2]>,
    /// The scene at its given parameters (`--param` or its defaults).
    pub base: Scene,
    pub params: ParamSet,
}

impl Family {
    /// One or two axes `name=lo:hi`; each end is checked as the parameter's
    /// value would be (decimal text), and `lo < hi`; the whole box must then
    /// satisfy the scene's `[conditions]`.
    pub fn new(
        source: Source,
        variant: Variant,
        overrides: Vec<(String, String)>,
        axes: Vec<ParamAxis>,
    ) -> Result<Family, String> {
        if axes.is_empty() || axes.len() > 2 {
            return Err("give one or two parameters to vary".into());
        }
        if axes.len() == 2 && axes[0].name == axes[1].name {
            return Err(format!(
                "both axes vary `{}`: give two different parameters",
                axes[0].name
            ));
        }
        let (base, params) = match &source {
            Source::Paper(id) => Scene::build(*id, &overrides).map_err(|e| e.to_string())?,
            Source::File(_) => build(&source, variant, &overrides, &[])?,
        };
        let mut root = Vec::new();
        for a in &axes {
            let spec = params
                .specs
                .iter()
                .find(|s| s.name == a.name)
                .ok_or_else(|| {
                    format!(
                        "unknown parameter `{}` for scene `{}` (known: {})",
                        a.name,
                        base.name(),
                        params
                            .specs
                            .iter()
                            .map(|s| s.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                })?;
            let end = |t: &str| {
                Param::parse(spec, t)
                    .map(|p| p.value)
                    .map_err(|e| e.to_string())
            };
            let (lo, hi) = (end(&a.lo)?, end(&a.hi)?);
            if lo.sup() >= hi.inf() {
                return Err(format!(
                    "parameter `{}`: the range {}:{} is empty (need lo < hi)",
                    a.name, a.lo, a.hi
                ));
            }
            root.push([lo.inf(), hi.sup()]);
        }
        let family = Family {
            source,
            variant,
            overrides,
            axes,
            root,
            base,
            params,
        };
        // The whole box must give a scene (e.g. the viscous disc's b < a).
        family.scene_at(&family.root)?;
        Ok(family)
    }

    /// The scene with every axis enclosed by `bounds` (exact doubles).
    pub fn scene_at(&self, bounds: &[[f64; 2]]) -> Result<Scene, String> {
        let boxes: Vec<(String, Interval)> = self
            .axes
            .iter()
            .zip(bounds)
            .map(|(a, b)| {
                let x = Interval::try_from((b[0], b[1])).map_err(|_| "bad parameter box")?;
                Ok((a.name.clone(), x))
            })
            .collect::<Result<_, &str>>()?;
        Ok(build(&self.source, self.variant, &self.overrides, &boxes)?.0)
    }

    /// The scene at one point of the parameter box (steering only).
    pub fn scene_at_point(&self, point: &[f64]) -> Result<Scene, String> {
        let b: Vec<[f64; 2]> = point.iter().map(|&x| [x, x]).collect();
        self.scene_at(&b)
    }

    /// The value of an axis in the scene as given (`--param` or default):
    /// the point a picture marks.
    pub fn given(&self, axis: usize) -> Interval {
        self.params.get(&self.axes[axis].name)
    }
}

/// The scene with `overrides` and then `boxes` applied: a paper scene as
/// the file of the reading `variant` (the one the search evaluates).
fn build(
    source: &Source,
    variant: Variant,
    overrides: &[(String, String)],
    boxes: &[(String, Interval)],
) -> Result<(Scene, ParamSet), String> {
    let text = match source {
        Source::Paper(id) => id.text(variant),
        Source::File(t) => t.clone(),
    };
    let f = FileScene::parse_enclosed(&text.text, overrides, boxes)
        .map_err(|m| format!("{}: {m}", text.file))?;
    let p = f.params.clone();
    Ok((Scene::File(Box::new(f)), p))
}
