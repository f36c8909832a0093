//! What a query answers: [`Proximity`] (overlapping with a [`Contact`], or
//! apart with a [`Separation`]) and the [`FeaturePair`] behind it.

use glam::DVec3;

/// The features of `A` and `B` generating a facet of `A ⊕ (−B)` (indices
/// into the original bodies). The order (face–vertex, vertex–face,
/// edge–edge, then by indices) settles the last ties between candidates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FeaturePair {
    /// Face `a_face` of A against vertex `b_vertex` of B.
    FaceVertex {
        /// Face of A.
        a_face: u32,
        /// Vertex of B.
        b_vertex: u32,
    },
    /// Vertex `a_vertex` of A against face `b_face` of B.
    VertexFace {
        /// Vertex of A.
        a_vertex: u32,
        /// Face of B.
        b_face: u32,
    },
    /// Edge `a_edge` of A against edge `b_edge` of B.
    EdgeEdge {
        /// Edge of A.
        a_edge: u32,
        /// Edge of B.
        b_edge: u32,
    },
}

/// Two overlapping (or touching) bodies: the penetration depth and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// The length of the shortest translation separating the bodies
    /// (`0` when they touch).
    pub depth: f64,
    /// Unit contact normal, from A towards B: translate A by
    /// `−depth · normal` (or B by `+depth · normal`) to separate them.
    pub normal: DVec3,
    /// A's deepest point inside B (on A's boundary).
    pub point_on_a: DVec3,
    /// B's deepest point inside A (on B's boundary);
    /// `point_on_a − point_on_b = depth · normal`.
    pub point_on_b: DVec3,
    /// The features whose facet of `A ⊕ (−B)` is nearest the origin.
    pub features: FeaturePair,
}

/// Two bodies apart: their distance and closest points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Separation {
    /// The distance between the bodies (`> 0`).
    pub distance: f64,
    /// The closest point of A.
    pub point_on_a: DVec3,
    /// The closest point of B.
    pub point_on_b: DVec3,
    /// Unit vector from A towards B (`point_on_b − point_on_a`, normalised).
    pub direction: DVec3,
    /// The features of the facet of `A ⊕ (−B)` nearest the origin.
    pub features: FeaturePair,
}

/// The answer of a query: overlapping (with the depth) or apart (with the
/// distance).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Proximity {
    /// Overlapping or touching.
    Penetrating(Contact),
    /// Apart.
    Separated(Separation),
}

impl Proximity {
    /// `true` when the bodies overlap or touch.
    pub fn intersects(&self) -> bool {
        matches!(self, Proximity::Penetrating(_))
    }
    /// The penetration depth (`0` when apart).
    pub fn depth(&self) -> f64 {
        match self {
            Proximity::Penetrating(c) => c.depth,
            Proximity::Separated(_) => 0.0,
        }
    }
    /// The distance (`0` when touching or overlapping).
    pub fn distance(&self) -> f64 {
        match self {
            Proximity::Penetrating(_) => 0.0,
            Proximity::Separated(s) => s.distance,
        }
    }
    /// The contact, when overlapping.
    pub fn contact(&self) -> Option<&Contact> {
        match self {
            Proximity::Penetrating(c) => Some(c),
            Proximity::Separated(_) => None,
        }
    }
    /// The separation, when apart.
    pub fn separation(&self) -> Option<&Separation> {
        match self {
            Proximity::Penetrating(_) => None,
            Proximity::Separated(s) => Some(s),
        }
    }
    /// A's shortest separating translation direction (unit) when
    /// overlapping (`−normal`), or the unit direction from A towards B when
    /// apart.
    pub fn a_direction(&self) -> DVec3 {
        match self {
            Proximity::Penetrating(c) => -c.normal,
            Proximity::Separated(s) => s.direction,
        }
    }
}
