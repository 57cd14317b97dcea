//! A paving cut down to a root box inside its own: the same split points,
//! the leaves intersected with the new box, the subtrees that fall outside
//! it dropped. A proof uses it to keep its root box clear of a domain end
//! that a looser checker encloses less tightly ([`super::confirm`]).

use crate::pave::{Leaf, Node, Paving, PhaseBox};

/// `paving` restricted to `root`, which must lie inside `paving.root`. Every
/// split keeps its point (written as an explicit point wherever it is no
/// longer the midpoint of the smaller box), and every leaf keeps its labels:
/// a label proved on a box holds on any part of it.
pub fn clipped_to(paving: &Paving, root: PhaseBox) -> Paving {
    if root == paving.root {
        return paving.clone();
    }
    let mut c = Clip {
        src: paving,
        pos: 0,
        nodes: Vec::with_capacity(paving.nodes.len()),
        leaves: Vec::with_capacity(paving.leaves.len()),
    };
    c.walk(paving.root, root);
    Paving {
        root,
        nodes: c.nodes,
        leaves: c.leaves,
        ..paving.clone()
    }
}

struct Clip<'a> {
    src: &'a Paving,
    pos: usize,
    nodes: Vec<Node>,
    leaves: Vec<Leaf>,
}

fn range(b: &PhaseBox, axis: usize) -> [f64; 2] {
    if axis == 0 {
        b.theta
    } else {
        b.theta_dot
    }
}

impl Clip<'_> {
    /// Moves past one subtree of the source.
    fn skip(&mut self) {
        let mut open = 1usize;
        while open > 0 {
            match self.src.nodes[self.pos] {
                Node::Leaf(_) => open -= 1,
                _ => open += 1,
            }
            self.pos += 1;
        }
    }

    /// Copies the subtree at `pos`, whose box is `orig`, onto `clip ⊂ orig`.
    fn walk(&mut self, orig: PhaseBox, clip: PhaseBox) {
        let node = self.src.nodes[self.pos];
        self.pos += 1;
        let (a, p) = match node {
            Node::Leaf(i) => {
                let mut leaf = self.src.leaves[i as usize];
                leaf.bx = clip;
                self.nodes.push(Node::Leaf(self.leaves.len() as u32));
                self.leaves.push(leaf);
                return;
            }
            Node::Split(a) => (a, orig.midpoint(usize::from(a))),
            Node::SplitAt(a, p) => (a, p),
        };
        let axis = usize::from(a);
        let (lo, hi) = orig
            .split_at(axis, p)
            .expect("a paving's split lies inside its box");
        let r = range(&clip, axis);
        match clip.split_at(axis, p) {
            Some((clip_lo, clip_hi)) => {
                self.nodes.push(if clip.midpoint(axis) == p {
                    Node::Split(a)
                } else {
                    Node::SplitAt(a, p)
                });
                self.walk(lo, clip_lo);
                self.walk(hi, clip_hi);
            }
            None if p <= r[0] => {
                self.skip();
                self.walk(hi, clip);
            }
            None => {
                self.walk(lo, clip);
                self.skip();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pave::{pave_scene, Label, PaveOptions};
    use crate::scene::{Scene, SceneId, Variant};

    fn replayed_boxes(p: &Paving) -> Vec<PhaseBox> {
        // The leaves' boxes as a checker replays the tree from the root.
        fn go(p: &Paving, pos: &mut usize, b: PhaseBox, out: &mut Vec<PhaseBox>) {
            let n = p.nodes[*pos];
            *pos += 1;
            let (a, at) = match n {
                Node::Leaf(_) => return out.push(b),
                Node::Split(a) => (usize::from(a), b.midpoint(usize::from(a))),
                Node::SplitAt(a, x) => (usize::from(a), x),
            };
            let (lo, hi) = b.split_at(a, at).expect("inside");
            go(p, pos, lo, out);
            go(p, pos, hi, out);
        }
        let mut out = Vec::new();
        go(p, &mut 0, p.root, &mut out);
        out
    }

    /// Cut by a few ulps at two ends and by a third of the box at another:
    /// the replayed tree gives exactly the stated leaf boxes, they tile the
    /// new root (their areas add up to it), each lies in a source leaf with
    /// the same labels, and a subtree wholly outside is gone.
    #[test]
    fn a_clipped_paving_replays_to_its_leaves_and_tiles_its_root() {
        let scene = Scene::default_of(SceneId::ViscousDisc);
        let opts = PaveOptions {
            eps: 1.0 / 64.0,
            ..PaveOptions::default()
        };
        let p = pave_scene(&scene, Variant::Derived, opts, |_, _, _| {}).unwrap();
        let r = p.root;
        let mut root = r;
        root.theta[0] = r.theta[0].next_up().next_up();
        root.theta[1] = r.theta[1] - (r.theta[1] - r.theta[0]) / 3.0;
        root.theta_dot[1] = r.theta_dot[1].next_down();
        let c = clipped_to(&p, root);
        assert_eq!(c.root, root);
        let boxes = replayed_boxes(&c);
        assert_eq!(boxes.len(), c.leaves.len());
        let mut area = 0.0;
        for (i, (b, leaf)) in boxes.iter().zip(&c.leaves).enumerate() {
            let at = c.nodes.iter().filter(|n| matches!(n, Node::Leaf(_))).nth(i);
            assert_eq!(at, Some(&Node::Leaf(i as u32)));
            assert_eq!(*b, leaf.bx);
            let src = p
                .leaves
                .iter()
                .find(|s| {
                    s.bx.contains(b.theta[0], b.theta_dot[0])
                        && s.bx.contains(b.theta[1], b.theta_dot[1])
                })
                .expect("inside a source leaf");
            assert_eq!(src.labels, leaf.labels);
            area += (b.theta[1] - b.theta[0]) * (b.theta_dot[1] - b.theta_dot[0]);
        }
        let whole = (root.theta[1] - root.theta[0]) * (root.theta_dot[1] - root.theta_dot[0]);
        assert!((area - whole).abs() <= 1e-12 * whole, "{area} vs {whole}");
        assert!(c.leaves.len() < p.leaves.len());
        assert!(c.leaves.iter().any(|l| l.labels[0] != Label::Undecided));
        // Unchanged root: the same paving.
        assert_eq!(clipped_to(&p, p.root).nodes, p.nodes);
    }
}
