//! A small bounding-box tree for [`super::check_solid_mesh`]: the pairs of
//! triangles whose closed boxes meet.
//!
//! Boxes are the exact `f64` minimum and maximum of the corners (no
//! rounding, no padding is needed), and two boxes meet when they overlap or
//! touch on every axis, so no pair of triangles that touches is left out.
//! Built by median splits of the box centres along the widest axis (the
//! centres only choose the split; any split is correct).

/// A closed axis-aligned box.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Aabb {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

impl Aabb {
    /// The box of some points.
    pub fn of(points: impl IntoIterator<Item = [f64; 3]>) -> Aabb {
        let mut b = Aabb {
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
        };
        for p in points {
            for (k, x) in p.into_iter().enumerate() {
                b.lo[k] = b.lo[k].min(x);
                b.hi[k] = b.hi[k].max(x);
            }
        }
        b
    }

    fn join(&self, o: &Aabb) -> Aabb {
        Aabb {
            lo: std::array::from_fn(|k| self.lo[k].min(o.lo[k])),
            hi: std::array::from_fn(|k| self.hi[k].max(o.hi[k])),
        }
    }

    /// The closed boxes share a point.
    #[inline]
    pub fn meets(&self, o: &Aabb) -> bool {
        (0..3).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }

    fn centre(&self, k: usize) -> f64 {
        // Halves first: no overflow near f64::MAX.
        0.5 * self.lo[k] + 0.5 * self.hi[k]
    }
}

/// At most this many items per leaf.
const LEAF: usize = 4;

enum Node {
    Leaf { start: u32, end: u32 },
    Inner { left: u32, right: u32 },
}

/// The tree over boxes `0..n`.
pub(crate) struct AabbTree {
    boxes: Vec<Aabb>,
    bounds: Vec<Aabb>,
    nodes: Vec<Node>,
    items: Vec<u32>,
}

impl AabbTree {
    /// Builds the tree of `boxes` (item `i` is `boxes[i]`).
    pub fn new(boxes: &[Aabb]) -> AabbTree {
        let mut tree = AabbTree {
            boxes: boxes.to_vec(),
            bounds: Vec::new(),
            nodes: Vec::new(),
            items: (0..boxes.len() as u32).collect(),
        };
        if !boxes.is_empty() {
            tree.build(boxes, 0, boxes.len());
        }
        tree
    }

    fn build(&mut self, boxes: &[Aabb], start: usize, end: usize) -> u32 {
        let items = &mut self.items[start..end];
        let bound = items
            .iter()
            .skip(1)
            .fold(boxes[items[0] as usize], |b, &i| b.join(&boxes[i as usize]));
        let id = self.nodes.len() as u32;
        self.bounds.push(bound);
        if end - start <= LEAF {
            self.nodes.push(Node::Leaf {
                start: start as u32,
                end: end as u32,
            });
            return id;
        }
        let axis = (0..3)
            .max_by(|&a, &b| {
                let w = |k: usize| bound.hi[k] - bound.lo[k];
                w(a).total_cmp(&w(b))
            })
            .unwrap_or(0);
        let mid = (end - start) / 2;
        items.select_nth_unstable_by(mid, |&a, &b| {
            boxes[a as usize]
                .centre(axis)
                .total_cmp(&boxes[b as usize].centre(axis))
        });
        self.nodes.push(Node::Leaf { start: 0, end: 0 });
        let left = self.build(boxes, start, start + mid);
        let right = self.build(boxes, start + mid, end);
        self.nodes[id as usize] = Node::Inner { left, right };
        id
    }

    /// Calls `f` with every item whose box meets `query`.
    pub fn for_each_meeting(&self, query: &Aabb, mut f: impl FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = vec![0u32];
        while let Some(n) = stack.pop() {
            if !self.bounds[n as usize].meets(query) {
                continue;
            }
            match self.nodes[n as usize] {
                Node::Leaf { start, end } => {
                    for &i in &self.items[start as usize..end as usize] {
                        if self.boxes[i as usize].meets(query) {
                            f(i as usize);
                        }
                    }
                }
                Node::Inner { left, right } => {
                    stack.push(right);
                    stack.push(left);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_every_meeting_box() {
        // A grid of unit boxes touching their neighbours: the tree finds
        // exactly the brute-force pairs, touching ones included.
        let mut boxes = Vec::new();
        for i in 0..7 {
            for j in 0..5 {
                let (x, y) = (i as f64, j as f64 * 1.5);
                boxes.push(Aabb::of([[x, y, 0.0], [x + 1.0, y + 1.0, 1.0]]));
            }
        }
        let tree = AabbTree::new(&boxes);
        for q in &boxes {
            let mut got = Vec::new();
            tree.for_each_meeting(q, |i| got.push(i));
            got.sort_unstable();
            let want: Vec<usize> = (0..boxes.len()).filter(|&i| boxes[i].meets(q)).collect();
            assert_eq!(got, want);
        }
    }
}
