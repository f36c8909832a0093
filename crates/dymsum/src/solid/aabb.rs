//! A small bounding-box tree for [`super::check_solid_mesh`] (the pairs of
//! triangles whose closed boxes meet) and for the scenes' broad phase
//! ([`crate::query`]'s mesh bodies: a body's tree is built once in its own
//! frame and its boxes carried to a pose where a walk reaches them; two
//! trees are walked against each other, [`AabbTree::for_each_pair`]).
//!
//! Boxes are the exact `f64` minimum and maximum of the corners (no
//! rounding, no padding is needed), and two boxes meet when they overlap or
//! touch on every axis, so no pair of triangles that touches is left out.
//! Built by the binned surface-area heuristic over the box centres
//! ([`AabbTree::new`]) or by median splits along the widest axis, a k-d
//! tree ([`AabbTree::over_points`]); the centres only choose the split, and
//! any split is correct. The items are carried with their boxes while the
//! tree is built, so each level reads memory in order. Walks: pairs of
//! meeting boxes ([`AabbTree::for_each_pair`]), the boxes meeting a query
//! ([`AabbTree::for_each_meeting`], no allocation below depth 64), and the
//! nearest pair, best first ([`AabbTree::nearest_pair`]).

use crate::sanity::SanityError;

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

    /// The empty box (meets nothing; the identity of [`Aabb::join`]).
    pub const EMPTY: Aabb = Aabb {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    /// The smallest box holding both.
    #[inline]
    pub fn join(&self, o: &Aabb) -> Aabb {
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

    /// The closed boxes come within `slack` of each other on every axis:
    /// `false` proves a gap larger than `slack` along some axis, hence a
    /// distance larger than `slack` between anything inside them (each
    /// comparison is of `fl(lo − slack)` with a coordinate, and rounding
    /// is monotone, so `fl(x − s) > y` implies `x − s > y`).
    #[inline]
    pub fn within(&self, o: &Aabb, slack: f64) -> bool {
        (0..3).all(|k| self.lo[k] - slack <= o.hi[k] && o.lo[k] - slack <= self.hi[k])
    }

    /// A box holding the image of this one under `x ↦ m x + t`, grown by
    /// `pad` on every side (the caller's bound on the rounding of the
    /// centre's image and of the posed points themselves).
    #[inline]
    pub fn transformed(&self, m: &glam::DMat3, t: glam::DVec3, pad: f64) -> Aabb {
        let (lo, hi) = (glam::DVec3::from(self.lo), glam::DVec3::from(self.hi));
        let (c, h) = (0.5 * lo + 0.5 * hi, 0.5 * hi - 0.5 * lo);
        let c2 = *m * c + t;
        let h2 = glam::DVec3::new(
            m.row(0).abs().dot(h),
            m.row(1).abs().dot(h),
            m.row(2).abs().dot(h),
        ) + glam::DVec3::splat(pad);
        Aabb {
            lo: (c2 - h2).to_array(),
            hi: (c2 + h2).to_array(),
        }
    }

    /// The distance between the boxes (`0` when they meet), in floating
    /// point.
    #[inline]
    pub fn distance(&self, o: &Aabb) -> f64 {
        let gap = |k: usize| (self.lo[k] - o.hi[k]).max(o.lo[k] - self.hi[k]).max(0.0);
        gaps_norm([gap(0), gap(1), gap(2)])
    }

    /// Whether the closed box holds `p`.
    #[inline]
    pub fn holds(&self, p: [f64; 3]) -> bool {
        (0..3).all(|k| self.lo[k] <= p[k] && p[k] <= self.hi[k])
    }

    /// The length of the longest side (for choosing which tree to
    /// descend).
    #[inline]
    pub fn size(&self) -> f64 {
        (0..3).map(|k| self.hi[k] - self.lo[k]).fold(0.0, f64::max)
    }

    fn centre(&self, k: usize) -> f64 {
        // Halves first: no overflow near f64::MAX.
        0.5 * self.lo[k] + 0.5 * self.hi[k]
    }
}

/// `√(g₀² + g₁² + g₂²)` of three gaps at least `0`, in floating point
/// (within a few `u` of it, relative) at every scale: the squares are
/// taken directly while the largest gap lies between `2⁻⁴⁰⁰` and `2⁴⁰⁰`
/// (no division: it is the slow part), else of the gaps scaled by the
/// largest (a subnormal square would round up by far more than `u`, and
/// a huge one overflow). `0`, `∞` or NaN when the largest gap is.
#[inline]
pub(crate) fn gaps_norm(g: [f64; 3]) -> f64 {
    let m = g[0].max(g[1]).max(g[2]);
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    if (f64::from_bits(0x26f0_0000_0000_0000)..f64::from_bits(0x58f0_0000_0000_0000)).contains(&m) {
        return (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    }
    let (a, b, c) = (g[0] / m, g[1] / m, g[2] / m);
    m * (a * a + b * b + c * c).sqrt()
}

/// The bins of the surface-area split.
const BINS: usize = 16;

/// Half the surface area of a box (the chance a random ray or box meets
/// it grows with it).
fn half_area(b: &Aabb) -> f64 {
    let d: [f64; 3] = std::array::from_fn(|k| (b.hi[k] - b.lo[k]).max(0.0));
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

/// The best bin boundary of one axis, from its bins' counts and boxes:
/// `(cost, last bin of the left side)`, or `None` when every item falls
/// on one side.
fn best_split_of(count: &[usize; BINS], bound: &[Aabb; BINS], n: usize) -> Option<(f64, usize)> {
    // Right sides' costs from the right, then the left sides from the left.
    let mut right_cost = [0.0f64; BINS];
    let (mut acc, mut c) = (Aabb::EMPTY, 0usize);
    for b in (1..BINS).rev() {
        acc = acc.join(&bound[b]);
        c += count[b];
        right_cost[b] = c as f64 * half_area(&acc);
    }
    let (mut acc, mut c) = (Aabb::EMPTY, 0usize);
    let mut best: Option<(f64, usize)> = None;
    for b in 0..BINS - 1 {
        acc = acc.join(&bound[b]);
        c += count[b];
        if c == 0 || c == n {
            continue;
        }
        let cost = c as f64 * half_area(&acc) + right_cost[b + 1];
        if best.is_none_or(|x| cost < x.0) {
            best = Some((cost, b));
        }
    }
    best
}

/// The bin of centre `x`.
fn bin_of(x: f64, lo: f64, scale: f64) -> usize {
    (((x - lo) * scale) as usize).min(BINS - 1)
}

/// Reorders `items` so that `items[..mid]` and `items[mid..]` are the two
/// children, and returns `mid` (strictly inside): the binned surface-area
/// heuristic over the box centres on each axis (the split minimising
/// `count · area` summed over both sides), or the median of the widest
/// axis of `bound` (the items' box) when every centre coincides. Any
/// split is correct; this one makes the boxes of a node overlap less, so
/// fewer pairs are visited. `(lo, hi)` is the box of the items' centres:
/// all three axes are binned in one pass over the items.
fn split_by_area(items: &mut [Item], bound: &Aabb, (lo, hi): ([f64; 3], [f64; 3])) -> usize {
    let n = items.len();
    let live: [bool; 3] = std::array::from_fn(|k| hi[k] > lo[k]);
    let scale: [f64; 3] = std::array::from_fn(|k| BINS as f64 / (hi[k] - lo[k]));
    let mut count = [[0usize; BINS]; 3];
    let mut bins = [[Aabb::EMPTY; BINS]; 3];
    for item in items.iter() {
        for k in 0..3 {
            if live[k] {
                let j = bin_of(item.centre[k], lo[k], scale[k]);
                count[k][j] += 1;
                bins[k][j] = bins[k][j].join(&item.bound);
            }
        }
    }
    let best = (0..3)
        .filter(|&k| live[k])
        .filter_map(|k| best_split_of(&count[k], &bins[k], n).map(|b| (k, b)))
        .min_by(|x, y| x.1 .0.total_cmp(&y.1 .0));
    if let Some((k, (_, last))) = best {
        let mut mid = 0;
        for j in 0..n {
            if bin_of(items[j].centre[k], lo[k], scale[k]) <= last {
                items.swap(mid, j);
                mid += 1;
            }
        }
        if mid > 0 && mid < n {
            return mid;
        }
    }
    split_at_median(items, bound)
}

/// Reorders `items` so that `items[..mid]` and `items[mid..]` are the two
/// halves along the widest axis of `bound` (the items' box), and returns
/// `mid = n / 2`: the split of a k-d tree, linear in the items (what a
/// tree over points needs; any split is correct).
fn split_at_median<I: BuildItem>(items: &mut [I], bound: &Aabb) -> usize {
    let axis = (0..3)
        .max_by(|&a, &b| {
            let w = |k: usize| bound.hi[k] - bound.lo[k];
            w(a).total_cmp(&w(b))
        })
        .unwrap_or(0);
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.centre()[axis].total_cmp(&b.centre()[axis]));
    mid
}

/// An item while its tree is built: its box, the box's centre and its
/// number, side by side, so that every pass over a node's items reads
/// memory in order (a tree of a million triangles no longer waits on a
/// cache miss per item and level).
trait BuildItem: Copy + Send {
    fn bound(&self) -> Aabb;
    fn centre(&self) -> [f64; 3];
    fn index(&self) -> u32;
}

/// A box as it is built into a tree.
#[derive(Clone, Copy)]
struct Item {
    bound: Aabb,
    centre: [f64; 3],
    index: u32,
}

impl BuildItem for Item {
    fn bound(&self) -> Aabb {
        self.bound
    }
    fn centre(&self) -> [f64; 3] {
        self.centre
    }
    fn index(&self) -> u32 {
        self.index
    }
}

/// A point as it is built into a tree (its box is itself: less than half
/// an [`Item`]'s memory, and the cleaning indexes every vertex).
#[derive(Clone, Copy)]
struct PointItem {
    at: [f64; 3],
    index: u32,
}

impl BuildItem for PointItem {
    fn bound(&self) -> Aabb {
        Aabb {
            lo: self.at,
            hi: self.at,
        }
    }
    fn centre(&self) -> [f64; 3] {
        self.at
    }
    fn index(&self) -> u32 {
        self.index
    }
}

/// How a node's items are split: the items, the node's box and the box of
/// its items' centres; returns the size of the first part (strictly
/// inside).
type Split<I> = fn(&mut [I], &Aabb, ([f64; 3], [f64; 3])) -> usize;

/// At most this many items per leaf of a tree over at most `SMALL_TREE`
/// items ([`AabbTree::leaf_size`]).
const LEAF: usize = 2;

/// At most this many items per leaf of a larger tree.
const LARGE_TREE_LEAF: usize = 4;

/// Trees over more items than this keep `LARGE_TREE_LEAF` per leaf.
const SMALL_TREE: usize = 1 << 12;

#[derive(Clone, Copy)]
enum Node {
    Leaf { start: u32, end: u32 },
    Inner { left: u32, right: u32 },
}

/// The tree over boxes `0..n`.
#[derive(Clone)]
pub(crate) struct AabbTree {
    /// At most this many items per leaf ([`AabbTree::leaf_size`]).
    leaf: usize,
    boxes: Vec<Aabb>,
    bounds: Vec<Aabb>,
    nodes: Vec<Node>,
    items: Vec<u32>,
}

impl std::fmt::Debug for AabbTree {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AabbTree")
            .field("items", &self.boxes.len())
            .field("nodes", &self.nodes.len())
            .finish()
    }
}

impl AabbTree {
    /// Builds the tree of `boxes` (item `i` is `boxes[i]`).
    pub fn new(boxes: &[Aabb]) -> AabbTree {
        let items = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| Item {
                bound: *b,
                centre: std::array::from_fn(|k| b.centre(k)),
                index: i as u32,
            })
            .collect();
        let leaf = AabbTree::leaf_size(boxes.len());
        AabbTree::with_split(boxes.to_vec(), items, split_by_area, leaf)
    }

    /// The tree over points (boxes of no extent; any boxes will do): split
    /// at the median of the widest axis, a k-d tree. The binned area
    /// heuristic of [`AabbTree::new`] has no areas to weigh here and costs
    /// several times more to build (the mesh cleaning's vertex index).
    pub fn over_points(points: &[[f64; 3]]) -> AabbTree {
        let items = points
            .iter()
            .enumerate()
            .map(|(i, &at)| PointItem {
                at,
                index: i as u32,
            })
            .collect();
        let boxes = points.iter().map(|&p| Aabb { lo: p, hi: p }).collect();
        // Points have no oriented boxes to keep thin: four a leaf.
        AabbTree::with_split(
            boxes,
            items,
            |items, bound, _| split_at_median(items, bound),
            LARGE_TREE_LEAF,
        )
    }

    /// The tree over `boxes` (`items` the same, as built), each node's
    /// items split by `split` (as [`split_by_area`]'s arguments), at most
    /// `leaf` items a leaf.
    fn with_split<I: BuildItem>(
        boxes: Vec<Aabb>,
        mut items: Vec<I>,
        split: Split<I>,
        leaf: usize,
    ) -> AabbTree {
        let mut tree = AabbTree {
            leaf,
            boxes,
            bounds: Vec::new(),
            nodes: Vec::new(),
            items: Vec::new(),
        };
        if !items.is_empty() {
            // At most 2n - 1 nodes (every leaf holds an item): reserved
            // once, so no doubling copies the arrays while the items are
            // held too (the pages never written are never resident).
            tree.bounds.reserve_exact(2 * items.len() - 1);
            tree.nodes.reserve_exact(2 * items.len() - 1);
            tree.build(&mut items, split, 0);
            tree.bounds.shrink_to_fit();
            tree.nodes.shrink_to_fit();
        }
        tree.items = items.iter().map(|item| item.index()).collect();
        tree
    }

    /// Builds the node over `items` (at `start` in the tree's order).
    fn build<I: BuildItem>(&mut self, items: &mut [I], split: Split<I>, start: usize) -> u32 {
        let (mut bound, mut lo) = (items[0].bound(), items[0].centre());
        let mut hi = lo;
        for item in &items[1..] {
            bound = bound.join(&item.bound());
            let c = item.centre();
            for k in 0..3 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        let id = self.nodes.len() as u32;
        self.bounds.push(bound);
        let n = items.len();
        if n <= self.leaf {
            self.nodes.push(Node::Leaf {
                start: start as u32,
                end: (start + n) as u32,
            });
            return id;
        }
        let mid = split(items, &bound, (lo, hi));
        self.nodes.push(Node::Leaf { start: 0, end: 0 });
        let (left_items, right_items) = items.split_at_mut(mid);
        let left = self.build(left_items, split, start);
        let right = self.build(right_items, split, start + mid);
        self.nodes[id as usize] = Node::Inner { left, right };
        id
    }

    /// At most how many items a leaf of a tree over `n` items holds: two
    /// (`LEAF`), or four (`LARGE_TREE_LEAF`) over more than `SMALL_TREE`
    /// items. A leaf's oriented box (`solid::obb`) fits its triangles:
    /// four large triangles of different slopes make a thick one that
    /// every nearby node of a finer mesh meets, and a near-contact state
    /// check of such a pair tested thousands of triangle pairs (a robot
    /// base of 7,992 triangles against a link of 84: 69% fewer
    /// instructions with two a leaf, 0–6% more on ordinary pairs). Such
    /// large triangles are a coarse mesh's; on a fine one the nodes, their
    /// oriented boxes and the queries' caches of them are much of the
    /// memory (a soup of 10⁴ triangles: 0.80 of python-fcl's peak with
    /// four a leaf, 0.99 with two), so trees over more than `SMALL_TREE`
    /// items keep four.
    fn leaf_size(n: usize) -> usize {
        if n <= SMALL_TREE {
            LEAF
        } else {
            LARGE_TREE_LEAF
        }
    }

    /// The bounds of the boxes the tree was built from.
    pub fn bounds(&self) -> &[Aabb] {
        &self.bounds
    }

    /// Node `n`'s items when it is a leaf.
    #[inline]
    pub fn leaf_items(&self, n: usize) -> Option<&[u32]> {
        match self.nodes[n] {
            Node::Leaf { start, end } => Some(&self.items[start as usize..end as usize]),
            Node::Inner { .. } => None,
        }
    }

    /// The items in tree order: node `n`'s items are
    /// `items()[s..e]` with `(s, e) = node_spans()[n]`.
    pub fn items(&self) -> &[u32] {
        &self.items
    }

    /// Each node's range in [`AabbTree::items`] (children are built after
    /// their parent, over contiguous ranges).
    pub fn node_spans(&self) -> Vec<(u32, u32)> {
        let mut spans = vec![(0u32, 0u32); self.nodes.len()];
        for n in (0..self.nodes.len()).rev() {
            spans[n] = match self.nodes[n] {
                Node::Leaf { start, end } => (start, end),
                Node::Inner { left, right } => (spans[left as usize].0, spans[right as usize].1),
            };
        }
        spans
    }

    /// The boxes the tree was built from.
    pub fn boxes(&self) -> &[Aabb] {
        &self.boxes
    }

    /// Checks the tree's invariants exactly: every item listed once, every
    /// leaf at most its leaf size of items, every node's bound holding its
    /// children's bounds or its items' boxes, children built after their
    /// parent.
    pub fn sanity_check(&self) -> Result<(), SanityError> {
        let bad = |node: usize, reason: &str| {
            Err(SanityError::BoxTree {
                node,
                reason: reason.to_string(),
            })
        };
        let holds = |outer: &Aabb, inner: &Aabb| {
            (0..3).all(|k| outer.lo[k] <= inner.lo[k] && inner.hi[k] <= outer.hi[k])
        };
        let mut seen = vec![false; self.boxes.len()];
        for &i in &self.items {
            let i = i as usize;
            if i >= seen.len() || std::mem::replace(&mut seen[i], true) {
                return bad(0, "an item is out of range or listed twice");
            }
        }
        if seen.iter().any(|&s| !s) {
            return bad(0, "an item is missing");
        }
        if self.bounds.len() != self.nodes.len() {
            return bad(0, "one bound per node");
        }
        for (n, node) in self.nodes.iter().enumerate() {
            let b = &self.bounds[n];
            match *node {
                Node::Leaf { start, end } => {
                    let (start, end) = (start as usize, end as usize);
                    if start >= end || end > self.items.len() || end - start > self.leaf {
                        return bad(n, "a leaf's item range is empty, too long or out of range");
                    }
                    if self.items[start..end]
                        .iter()
                        .any(|&i| !holds(b, &self.boxes[i as usize]))
                    {
                        return bad(n, "a leaf's bound misses one of its items' boxes");
                    }
                }
                Node::Inner { left, right } => {
                    let (l, r) = (left as usize, right as usize);
                    if l <= n || r <= n || l >= self.nodes.len() || r >= self.nodes.len() {
                        return bad(n, "a child is not built after its parent");
                    }
                    if !holds(b, &self.bounds[l]) || !holds(b, &self.bounds[r]) {
                        return bad(n, "a bound misses a child's bound");
                    }
                }
            }
        }
        Ok(())
    }

    /// The box of everything (the empty box for an empty tree).
    pub fn root(&self) -> Aabb {
        self.bounds.first().copied().unwrap_or(Aabb::EMPTY)
    }

    /// Walks this tree against `other`, calling `f(i, j)` for every pair of
    /// items that may come within reach of each other until `f` returns
    /// `true`; returns whether it did. This tree's tests are functions:
    /// `node_meets(n, k, b)` says whether node `n` may come within reach
    /// of the other tree's node `k`, whose box is `b`, `item_meets(i, b)`
    /// whether item `i` may come within reach of the other tree's leaf
    /// box `b`, and `items_meet(i, b)` whether it may come within reach of
    /// the other tree's item box `b` (`false`
    /// must prove it does not; e.g. the body-frame bounds carried to a
    /// pose, computed only for the nodes visited), `node_size(n)` which
    /// tree to descend first; `other`'s boxes and bounds are given.
    #[allow(clippy::too_many_arguments)]
    // Always inlined: the state check's walk lost 8% to a call here when
    // the containment test beside it grew (`query::scene::state`).
    #[inline(always)]
    pub fn for_each_pair(
        &self,
        node_meets: impl Fn(usize, usize, &Aabb) -> bool,
        node_size: impl Fn(usize) -> f64,
        item_meets: impl Fn(usize, &Aabb) -> bool,
        items_meet: impl Fn(usize, &Aabb) -> bool,
        other: &AabbTree,
        other_boxes: &[Aabb],
        other_bounds: &[Aabb],
        stack: &mut Vec<(u32, u32)>,
        mut f: impl FnMut(usize, usize) -> bool,
    ) -> bool {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return false;
        }
        stack.clear();
        stack.push((0, 0));
        while let Some((a, b)) = stack.pop() {
            let bb = &other_bounds[b as usize];
            if !node_meets(a as usize, b as usize, bb) {
                continue;
            }
            match (&self.nodes[a as usize], &other.nodes[b as usize]) {
                (Node::Leaf { start, end }, Node::Leaf { start: s2, end: e2 }) => {
                    for &i in &self.items[*start as usize..*end as usize] {
                        if !item_meets(i as usize, bb) {
                            continue;
                        }
                        for &j in &other.items[*s2 as usize..*e2 as usize] {
                            if items_meet(i as usize, &other_boxes[j as usize])
                                && f(i as usize, j as usize)
                            {
                                return true;
                            }
                        }
                    }
                }
                _ => self.descend(other, a, b, node_size(a as usize) >= bb.size(), stack),
            }
        }
        false
    }

    /// The least of `dist(i, j, best)` over item pairs (`best` the least so
    /// far: a pair may answer any lower bound of its own at least that
    /// large), with this tree's boxes given by functions (as in
    /// [`AabbTree::for_each_pair`]). Best first: node pairs are taken in
    /// the order of a certified lower bound on their distance, the farther
    /// of their boxes' distance (less a relative `1e-12`, so its rounding
    /// drops nothing that could matter) and `node_gap(a, b)` (e.g. the
    /// oriented boxes', `0.0` for none), and the walk ends when the next
    /// bound exceeds the best (every pair left is at least as far) or the
    /// best is zero (`dist` answers distances, never below zero).
    /// `queue` is scratch. `f64::INFINITY` when either tree is empty.
    pub fn nearest_pair(
        &self,
        node_box: impl Fn(usize) -> Aabb,
        item_box: impl Fn(usize) -> Aabb,
        node_gap: impl Fn(usize, usize) -> f64,
        other: &AabbTree,
        queue: &mut Vec<NearPair>,
        mut dist: impl FnMut(usize, usize, f64) -> f64,
    ) -> f64 {
        let mut best = f64::INFINITY;
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return best;
        }
        let shrink = |d: f64| d * (1.0 - 1e-12);
        // The boxes' distance, and `node_gap` (the costlier) only when the
        // boxes leave the pair below `best`: a pair beyond it is dropped
        // either way.
        let bound = |a: u32, b: u32, best: f64| {
            let boxes = shrink(node_box(a as usize).distance(&other.bounds[b as usize]));
            if boxes > best {
                return boxes;
            }
            boxes.max(node_gap(a as usize, b as usize))
        };
        queue.clear();
        let mut heap = std::collections::BinaryHeap::from(std::mem::take(queue));
        heap.push(NearPair(bound(0, 0, best), 0, 0));
        while let Some(NearPair(lower, a, b)) = heap.pop() {
            // Nothing is nearer than touching: a zero is final.
            if lower > best || best <= 0.0 {
                break;
            }
            match (&self.nodes[a as usize], &other.nodes[b as usize]) {
                (Node::Leaf { start, end }, Node::Leaf { start: s2, end: e2 }) => {
                    'leaf: for &i in &self.items[*start as usize..*end as usize] {
                        let bi = item_box(i as usize);
                        for &j in &other.items[*s2 as usize..*e2 as usize] {
                            if shrink(bi.distance(&other.boxes[j as usize])) <= best {
                                best = best.min(dist(i as usize, j as usize, best));
                                if best <= 0.0 {
                                    break 'leaf;
                                }
                            }
                        }
                    }
                }
                _ => {
                    let split_self = node_box(a as usize).size() >= other.bounds[b as usize].size();
                    for (x, y) in self.children(other, a, b, split_self).into_iter().flatten() {
                        let lower = bound(x, y, best);
                        if lower <= best {
                            heap.push(NearPair(lower, x, y));
                        }
                    }
                }
            }
        }
        *queue = heap.into_vec();
        best
    }

    /// The two node pairs below `(a, b)`: `a`'s children when `split_self`
    /// (or `b` is a leaf) and `a` has any, else `b`'s; `None` for two
    /// leaves.
    fn children(
        &self,
        other: &AabbTree,
        a: u32,
        b: u32,
        split_self: bool,
    ) -> Option<[(u32, u32); 2]> {
        match (&self.nodes[a as usize], &other.nodes[b as usize]) {
            (Node::Inner { left, right }, Node::Leaf { .. }) => Some([(*left, b), (*right, b)]),
            (Node::Inner { left, right }, Node::Inner { .. }) if split_self => {
                Some([(*left, b), (*right, b)])
            }
            (_, Node::Inner { left, right }) => Some([(a, *left), (a, *right)]),
            (Node::Leaf { .. }, Node::Leaf { .. }) => None,
        }
    }

    fn descend(
        &self,
        other: &AabbTree,
        a: u32,
        b: u32,
        split_self: bool,
        stack: &mut Vec<(u32, u32)>,
    ) {
        if let Some([first, second]) = self.children(other, a, b, split_self) {
            stack.push(second);
            stack.push(first);
        }
    }

    /// Calls `f` with every item whose box meets `query`.
    pub fn for_each_meeting(&self, query: &Aabb, mut f: impl FnMut(usize)) {
        self.meeting_while(
            |n| self.bounds[n],
            |i| self.boxes[i],
            query,
            |i| {
                f(i);
                true
            },
        );
    }

    /// Calls `f` with the items whose box meets `query`, in the order of
    /// [`AabbTree::for_each_meeting`], until `f` returns `false` (the
    /// first `k` of a long list without listing the rest).
    pub fn for_each_meeting_while(&self, query: &Aabb, f: impl FnMut(usize) -> bool) {
        self.meeting_while(|n| self.bounds[n], |i| self.boxes[i], query, f);
    }

    /// [`AabbTree::for_each_meeting`] with node `n`'s box `node_box(n)` and
    /// item `i`'s `item_box(i)` (e.g. computed at a pose only for what the
    /// walk reaches; any boxes holding the items serve, larger ones only
    /// call `f` more often).
    pub fn for_each_meeting_with(
        &self,
        node_box: impl Fn(usize) -> Aabb,
        item_box: impl Fn(usize) -> Aabb,
        query: &Aabb,
        mut f: impl FnMut(usize),
    ) {
        self.meeting_while(node_box, item_box, query, |i| {
            f(i);
            true
        });
    }

    /// The one traversal of the three above: depth first, left before
    /// right, items in leaf order, stopping when `f` returns `false`.
    pub(crate) fn meeting_while(
        &self,
        node_box: impl Fn(usize) -> Aabb,
        item_box: impl Fn(usize) -> Aabb,
        query: &Aabb,
        mut f: impl FnMut(usize) -> bool,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = NodeStack::new();
        stack.push(0);
        while let Some(n) = stack.pop() {
            if !node_box(n as usize).meets(query) {
                continue;
            }
            match self.nodes[n as usize] {
                Node::Leaf { start, end } => {
                    for &i in &self.items[start as usize..end as usize] {
                        if item_box(i as usize).meets(query) && !f(i as usize) {
                            return;
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

/// A node pair waiting in [`AabbTree::nearest_pair`]'s queue: its lower
/// bound and the two nodes, ordered so that the least bound comes first
/// out of a `BinaryHeap`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NearPair(f64, u32, u32);

impl PartialEq for NearPair {
    fn eq(&self, other: &NearPair) -> bool {
        self.cmp(other) == std::cmp::Ordering::Equal
    }
}

impl Eq for NearPair {}

impl PartialOrd for NearPair {
    fn partial_cmp(&self, other: &NearPair) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for NearPair {
    /// Reversed (a max-heap pops the least bound), the nodes breaking ties
    /// so the order is total and the walk deterministic.
    fn cmp(&self, other: &NearPair) -> std::cmp::Ordering {
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| (other.1, other.2).cmp(&(self.1, self.2)))
    }
}

/// A depth-first walk's stack of nodes: the first 64 inline, so that a
/// query on a tree less than 64 deep allocates nothing (the mesh cleaning
/// asks one per unbalanced edge, a state check several).
struct NodeStack {
    inline: [u32; 64],
    len: usize,
    spill: Vec<u32>,
}

impl NodeStack {
    fn new() -> NodeStack {
        NodeStack {
            inline: [0; 64],
            len: 0,
            spill: Vec::new(),
        }
    }

    fn push(&mut self, n: u32) {
        if self.len < self.inline.len() {
            self.inline[self.len] = n;
            self.len += 1;
        } else {
            self.spill.push(n);
        }
    }

    /// The last node pushed (the spill holds the newest once the inline
    /// part is full).
    fn pop(&mut self) -> Option<u32> {
        self.spill.pop().or_else(|| {
            self.len = self.len.checked_sub(1)?;
            Some(self.inline[self.len])
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_trees_keep_two_items_a_leaf_and_large_ones_four() {
        let boxes = |n: usize| -> Vec<Aabb> {
            (0..n)
                .map(|i| {
                    let x = i as f64;
                    Aabb::of([[x, 0.0, 0.0], [x + 0.5, 1.0, 1.0]])
                })
                .collect()
        };
        let most_in_a_leaf = |t: &AabbTree| {
            t.nodes
                .iter()
                .filter_map(|n| match *n {
                    Node::Leaf { start, end } => Some((end - start) as usize),
                    Node::Inner { .. } => None,
                })
                .max()
                .unwrap()
        };
        let small = AabbTree::new(&boxes(SMALL_TREE));
        small.sanity_check().unwrap();
        assert!(most_in_a_leaf(&small) <= LEAF);
        let large = AabbTree::new(&boxes(SMALL_TREE + 1));
        large.sanity_check().unwrap();
        assert!(most_in_a_leaf(&large) > LEAF && most_in_a_leaf(&large) <= LARGE_TREE_LEAF);
        // The points' k-d tree keeps four at any size.
        let points: Vec<[f64; 3]> = (0..1000).map(|i| [i as f64, 0.0, 0.0]).collect();
        assert!(most_in_a_leaf(&AabbTree::over_points(&points)) > LEAF);
    }

    #[test]
    fn box_distance_is_right_at_every_scale() {
        // A 3-4-12 gap (distance 13) scaled from far below to far above
        // the range where the squares are taken directly: within a few
        // ulps everywhere, never overflowing or vanishing.
        for e in [
            -1070, -1000, -600, -401, -400, -399, -10, 0, 10, 399, 400, 401, 600, 1000,
        ] {
            // In two factors: `2⁻¹⁰⁷⁰` is subnormal, its reciprocal not finite.
            let s = 2f64.powi(e / 2) * 2f64.powi(e - e / 2);
            let a = Aabb::of([[0.0, 0.0, 0.0], [s, s, s]]);
            let b = Aabb::of([[4.0 * s, 5.0 * s, 13.0 * s], [5.0 * s, 6.0 * s, 14.0 * s]]);
            let (d, want) = (a.distance(&b), 13.0 * s);
            if s > 1e-300 && want < f64::MAX / 2.0 {
                assert!(
                    (d - want).abs() <= 4.0 * f64::EPSILON * want,
                    "2^{e}: {d} {want}"
                );
            } else {
                assert!(d > 0.0 && d.is_finite() || want.is_infinite(), "2^{e}: {d}");
            }
            assert_eq!(a.distance(&a), 0.0);
        }
    }

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

    #[test]
    fn walks_keep_their_order_past_the_inline_stack() {
        // Nested boxes all holding the origin: the walk visits every node.
        // The stack itself stays last in, first out once it spills past
        // its 64 inline entries.
        let boxes: Vec<Aabb> = (0..300)
            .map(|i| {
                let r = 1.0 + i as f64;
                Aabb::of([[-r, -r, -r], [r, r, 2.0 * r]])
            })
            .collect();
        let tree = AabbTree::new(&boxes);
        tree.sanity_check().expect("a valid tree");
        let point = Aabb::of([[0.0; 3]]);
        let mut got = Vec::new();
        tree.for_each_meeting(&point, |i| got.push(i));
        got.sort_unstable();
        assert_eq!(got, (0..300).collect::<Vec<_>>());
        let mut stack = NodeStack::new();
        for n in 0..200 {
            stack.push(n);
        }
        let popped: Vec<u32> = std::iter::from_fn(|| stack.pop()).collect();
        assert_eq!(popped, (0..200).rev().collect::<Vec<_>>());
    }

    #[test]
    fn point_trees_find_every_point_in_a_box() {
        let mut rng = crate::kernel::test_rng::Xorshift::new(7);
        let points: Vec<[f64; 3]> = (0..2000)
            .map(|_| std::array::from_fn(|_| (rng.unit() * 16.0).floor()))
            .collect();
        let tree = AabbTree::over_points(&points);
        tree.sanity_check().expect("a valid tree");
        for q in points.chunks(2).take(200) {
            let query = Aabb::of([q[0], q[1]]);
            let mut got = Vec::new();
            tree.for_each_meeting(&query, |i| got.push(i));
            got.sort_unstable();
            let want: Vec<usize> = (0..points.len())
                .filter(|&i| query.holds(points[i]))
                .collect();
            assert_eq!(got, want);
        }
    }
}
