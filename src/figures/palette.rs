//! Checks that colours stay apart for readers with colour-vision
//! deficiencies: simulation after Machado, Oliveira & Fernandes (2009,
//! severity 1) and CIE 1976 colour differences.

type Rgb = (u8, u8, u8);

fn to_linear(c: u8) -> f64 {
    let c = f64::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear RGB as seen with a deficiency (`"deuteranopia"`, `"protanopia"`
/// or `"tritanopia"`); `None` for the unchanged colour.
fn simulate(c: Rgb, kind: Option<&str>) -> [f64; 3] {
    let l = [to_linear(c.0), to_linear(c.1), to_linear(c.2)];
    let m: [[f64; 3]; 3] = match kind {
        None => return l,
        Some("protanopia") => [
            [0.152286, 1.052583, -0.204868],
            [0.114503, 0.786281, 0.099216],
            [-0.003882, -0.048116, 1.051998],
        ],
        Some("tritanopia") => [
            [1.255528, -0.076749, -0.178779],
            [-0.078411, 0.930809, 0.147602],
            [0.004733, 0.691367, 0.303900],
        ],
        _ => [
            [0.367322, 0.860646, -0.227968],
            [0.280085, 0.672501, 0.047413],
            [-0.011820, 0.042940, 0.968881],
        ],
    };
    let mut o = [0.0; 3];
    for (i, row) in m.iter().enumerate() {
        o[i] = (row[0] * l[0] + row[1] * l[1] + row[2] * l[2]).clamp(0.0, 1.0);
    }
    o
}

fn lab(l: [f64; 3]) -> [f64; 3] {
    let x = 0.4124 * l[0] + 0.3576 * l[1] + 0.1805 * l[2];
    let y = 0.2126 * l[0] + 0.7152 * l[1] + 0.0722 * l[2];
    let z = 0.0193 * l[0] + 0.1192 * l[1] + 0.9505 * l[2];
    let f = |t: f64| {
        if t > 216.0 / 24389.0 {
            t.cbrt()
        } else {
            (24389.0 / 27.0 * t + 16.0) / 116.0
        }
    };
    let (fx, fy, fz) = (f(x / 0.95047), f(y), f(z / 1.08883));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// CIE 1976 ΔE between two colours as seen with deficiency `kind`
/// (`None`: normal vision).
pub fn delta_e(a: Rgb, b: Rgb, kind: Option<&str>) -> f64 {
    let (p, q) = (lab(simulate(a, kind)), lab(simulate(b, kind)));
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// The smallest ΔE between any two of `colours`, over normal vision and the
/// three dichromacies, with the pair and the vision that attain it.
pub fn min_delta_e(colours: &[Rgb]) -> (f64, usize, usize, &'static str) {
    let mut worst = (f64::INFINITY, 0, 0, "");
    for kind in [
        None,
        Some("deuteranopia"),
        Some("protanopia"),
        Some("tritanopia"),
    ] {
        for i in 0..colours.len() {
            for j in i + 1..colours.len() {
                let d = delta_e(colours[i], colours[j], kind);
                if d < worst.0 {
                    worst = (d, i, j, kind.unwrap_or("normal"));
                }
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::Class;

    #[test]
    fn atlas_classes_stay_apart_for_colour_blind_readers() {
        let colours: Vec<Rgb> = Class::ALL.iter().map(|c| c.rgb()).collect();
        let (d, i, j, kind) = min_delta_e(&colours);
        eprintln!(
            "atlas classes: min ΔE {d:.1} ({:?} vs {:?}, {kind})",
            Class::ALL[i],
            Class::ALL[j]
        );
        assert!(
            d >= 12.0,
            "{:?} and {:?} too close for {kind}: ΔE {d:.1}",
            Class::ALL[i],
            Class::ALL[j]
        );
    }

    #[test]
    fn chart_colours_stay_apart_for_colour_blind_readers() {
        use crate::figures::roots::{atlas_color, okabe_ito as oi};
        use crate::roots::critical::AtlasLabel;
        let rgb = |c: plotters::style::RGBColor| (c.0, c.1, c.2);
        let cc: Vec<Rgb> = [
            AtlasLabel::NoRoot,
            AtlasLabel::TwoSimpleRoots,
            AtlasLabel::Undecided,
        ]
        .iter()
        .map(|&l| rgb(atlas_color(l)))
        .collect();
        let (d, _, _, kind) = min_delta_e(&cc);
        assert!(d >= 12.0, "critical-curve fills: ΔE {d:.1} ({kind})");
        let lines = [rgb(oi::BLUE), rgb(oi::VERMILLION), rgb(oi::BLACK)];
        let (d, _, _, kind) = min_delta_e(&lines);
        assert!(d >= 12.0, "line colours: ΔE {d:.1} ({kind})");
        // The classic red/blue pair is what was replaced: still apart, but the
        // check must be able to fail on a bad pair (red and green).
        let (d, _, _, kind) = min_delta_e(&[(0xD0, 0x30, 0x30), (0x30, 0x90, 0x30)]);
        assert!(d < 12.0, "red/green should fail ({kind}: {d:.1})");
    }
}
