//! One proximity query of two convex bodies, step by step (the order is
//! [`evaluate`]'s): support functions ([`support`]), GJK's exact yes/no
//! ([`gjk`]), EPA's polytope inside the difference ([`epa`]), the
//! certificates that a small set of the overlay's facets decides the
//! answer ([`certificate`]), and the answer from those facets: penetration
//! depth ([`depth`]), distance ([`distance`]) and closest points
//! ([`closest`]).

pub(in crate::query) mod certificate;
pub(in crate::query) mod closest;
pub(in crate::query) mod depth;
pub(in crate::query) mod distance;
pub(in crate::query) mod epa;
pub(in crate::query) mod evaluate;
pub(in crate::query) mod gjk;
pub(in crate::query) mod support;
