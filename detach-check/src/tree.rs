//! The `tree/1` bisection tree (`proofs/FORMAT.md`): replayed in preorder
//! from a root box, each leaf's box and labels handed to the claim's check.

use inari::Interval;

use super::encoding::BitReader;

/// `[a, b]`, empty when it is not an interval.
pub fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap_or(Interval::EMPTY)
}

/// A box `[t_lo, t_hi, w_lo, w_hi]` as messages show it.
pub fn show_box(b: &[f64; 4]) -> String {
    format!("[{:e}, {:e}] x [{:e}, {:e}]", b[0], b[1], b[2], b[3])
}

/// What the walk saw: its nodes and leaves.
pub struct Walked {
    pub nodes: u64,
    pub leaves: u64,
}

/// Replays the tree in `bits` from `root` (`[t_lo, t_hi, w_lo, w_hi]`),
/// calling `leaf(box, bits, node)` per leaf in preorder after its `0` bit:
/// it reads the leaf's own bits (its labels, its reason). Fails on a split
/// point outside its box, a bit string ending inside a node, more than
/// `most` nodes, or bits after the last node other than the zero padding
/// of the last byte.
pub fn walk(
    bits: &mut BitReader,
    root: [f64; 4],
    most: u64,
    mut leaf: impl FnMut([f64; 4], &mut BitReader, u64) -> Result<(), String>,
) -> Result<Walked, String> {
    let mut stack = vec![root];
    let mut nodes = 0u64;
    let mut leaves = 0u64;
    while let Some(b) = stack.pop() {
        nodes += 1;
        if nodes > most {
            return Err(format!("the tree has more than the claimed {most} nodes"));
        }
        let end = || format!("the bit string ends inside node {nodes}");
        if !bits.bit().ok_or_else(end)? {
            leaves += 1;
            leaf(b, bits, nodes)?;
            continue;
        }
        let (axis, p) = if bits.bit().ok_or_else(end)? {
            let axis = usize::from(bits.bit().ok_or_else(end)?);
            (axis, f64::from_bits(bits.bits(64).ok_or_else(end)?))
        } else {
            let axis = usize::from(bits.bit().ok_or_else(end)?);
            (axis, 0.5 * b[2 * axis] + 0.5 * b[2 * axis + 1])
        };
        let (lo, hi) = (b[2 * axis], b[2 * axis + 1]);
        if !(p.is_finite() && lo < p && p < hi) {
            return Err(format!(
                "node {nodes}: split point {p:e} on {} is not inside ({lo:e}, {hi:e})",
                if axis == 0 { "t" } else { "w" }
            ));
        }
        let (mut lower, mut upper) = (b, b);
        lower[2 * axis + 1] = p;
        upper[2 * axis] = p;
        stack.push(upper);
        stack.push(lower);
    }
    if bits.len() - bits.position() >= 8 || !bits.rest_is_zero() {
        return Err(format!(
            "bits after the last node (bit {}) are not a zero padding of the last byte",
            bits.position()
        ));
    }
    Ok(Walked { nodes, leaves })
}

/// The `n` 2-bit labels of a leaf (node `node`).
pub fn labels(bits: &mut BitReader, n: usize, node: u64) -> Result<[u8; 4], String> {
    let mut out = [0u8; 4];
    for l in out.iter_mut().take(n) {
        *l = bits
            .bits(2)
            .ok_or_else(|| format!("the bit string ends inside node {node}"))? as u8;
    }
    Ok(out)
}
