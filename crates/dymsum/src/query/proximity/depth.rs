//! **How penetration depth is computed.** When GJK's exact certificate
//! shows the origin inside `D = A ⊕ (−B)` ([`super::gjk`]), EPA grows a
//! polytope `K ⊆ D` around the origin ([`super::epa`]); its nearest face
//! bounds the depth from above. The caps certificate
//! ([`super::certificate`], "Penetration: caps around EPA's polytope")
//! proves that only the overlay's facets whose normals lie in small caps
//! around `K`'s near faces can have a support value below that bound, and
//! finds exactly those facets with the overlay's own exact predicates. The
//! depth is the least support value among their candidates
//! ([`super::evaluate::evaluate_in_frame`], ties by the documented rule),
//! re-checked against the bound; when no certificate can be made the
//! exhaustive facet set answers ([`super::evaluate`]), counted in
//! [`crate::query::QueryStats`].

use crate::query::answer::Proximity;
use crate::query::pair::ConvexPair;
use crate::query::proximity::certificate::{
    grow_polytope, penetration_facets, polytope_depth, value_slack,
};
use crate::query::proximity::from_facets::evaluate_in_frame;
use crate::query::proximity::gjk::Gjk;
use crate::query::proximity::scratch::Scratch;

/// The certified penetration (frame units) from GJK's enclosing
/// tetrahedron: EPA's polytope, its caps, and the check of the bound the
/// caps assumed; `None` when a certificate cannot be made. With `carried`
/// (the scratch's EPA polytope is the last query's, of this pair: a
/// tracker's last frame) that polytope is re-posed and grown first
/// ([`crate::query::proximity::epa::Epa::regrow`]); where that fails, from
/// GJK's simplex as without.
pub(in crate::query) fn penetration(
    pair: &ConvexPair,
    scratch: &mut Scratch,
    g: &Gjk,
    carried: bool,
) -> Option<Proximity> {
    if carried {
        let answer = penetration_from(pair, scratch, g, true);
        pair.stats.count_carried_polytope(answer.is_none());
        if answer.is_some() {
            return answer;
        }
    }
    penetration_from(pair, scratch, g, false)
}

/// [`penetration`] from the carried polytope or from GJK's simplex.
fn penetration_from(
    pair: &ConvexPair,
    scratch: &mut Scratch,
    g: &Gjk,
    carried: bool,
) -> Option<Proximity> {
    let posed = &scratch.posed;
    let (tol, slack) = (posed.tol, value_slack(posed));
    let local = &mut scratch.local;
    if !grow_polytope(pair, posed, g, scratch.normal, carried, local) {
        return None;
    }
    let mut c = polytope_depth(local) + 4.0 * (tol + slack);
    for _ in 0..2 {
        if !penetration_facets(pair, posed, c, &mut scratch.cert, local) || local.facets.is_empty()
        {
            return None;
        }
        let (answer, hmin) = evaluate_in_frame(
            pair,
            posed,
            &local.facets,
            true,
            &mut scratch.cands,
            (&mut scratch.poly, &mut scratch.bounds),
        );
        let need = hmin + tol + slack;
        if need <= c {
            if let Proximity::Penetrating(contact) = &answer {
                scratch.normal = Some(contact.normal);
            }
            scratch.epa_carried = true;
            return Some(answer);
        }
        c = need * (1.0 + 1e-12);
    }
    None
}
