//! A `Track` shape's pieces walked into the geometry the engine, the window and validation use:
//! one polyline through every piece (an arc piece at its facet vertices, within the chord error
//! an `Arc` has), the true circle of each arc piece (which a ball touches exactly, as it touches
//! an `Arc`: `sim/track_shape.rs`), and the piece each edge belongs to (so that validation names
//! the pieces a fault lies in).
//!
//! One collider, not several bodies: a ball crossing from one fixed body to the next one
//! (an `Arc` ramp ending on a `Segment` floor) rides a little way into the first's soft contact
//! and strikes the second's end (docs/known-gaps.md, "joint strike"); one polyline has no end
//! there to strike.

use super::curves;
use super::format::{TrackPiece, TrackSide, V2};
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, TAU};

/// The most points one track may have (its arcs' facets and its lines' ends).
pub const MAX_TRACK_POINTS: usize = 200_000;

/// One piece as walked, in the body's frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Walked {
    /// A straight piece from `from` to `to`.
    Line { from: V2, to: V2 },
    /// A circular piece about `center`, counter-clockwise from angle `start` to `end` (rad, end >
    /// start whichever way the track runs), ridden on its concave side when `inside`.
    Arc {
        center: V2,
        radius: f64,
        start: f64,
        end: f64,
        inside: bool,
    },
}

/// A track walked: its points in the order written, and its pieces.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackPath {
    pub points: Vec<V2>,
    /// The piece (index into `pieces`) that edge k (points k to k + 1) belongs to.
    pub edge_piece: Vec<usize>,
    pub pieces: Vec<Walked>,
}

/// What is wrong with a track, by piece index (from 0, in the order written).
#[derive(Debug, Clone, PartialEq)]
pub enum TrackFault {
    /// No pieces.
    Empty,
    /// A value of piece k (or of the track itself: `None`) is not finite.
    NotFinite(Option<usize>, &'static str),
    /// Piece k has no length: a `Line` to where it starts, an `Arc` about its own start or of
    /// sweep 0, a `Turn` of angle 0.
    ZeroLength(usize),
    /// Piece k turns a whole turn or more (rad): a track is open.
    WholeTurn(usize, f64),
    /// A `Turn` (piece k) with nothing to turn from: first, without the track's `heading`.
    NoHeading(usize),
    /// A `Turn`'s radius (piece k) is not positive.
    Radius(usize, f64),
    /// Piece k would need more facets than one arc may have.
    TooManyFacets(usize),
    /// The track would have more than [`MAX_TRACK_POINTS`] points.
    TooManyPoints(usize),
    /// Pieces i and j cross or touch near a point (i <= j).
    Crossing(usize, usize, V2),
    /// Piece j turns straight back along piece i (the one before it, or itself) at a point.
    FoldsBack(usize, usize, V2),
}

/// How finely arc pieces are faceted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Facets {
    /// As the engine builds them: within the track's chord error (m; default 1e-7 radius).
    Engine(Option<f64>),
    /// For drawing: pieces of at most this angle, rad.
    Step(f64),
}

/// The walker's place: where the track has got to and the way it is heading (rad), if known.
struct At {
    p: DVec2,
    heading: Option<f64>,
}

/// Walks the pieces from `start`. `solid` is the side of the track's ground looking along it.
pub fn walk(
    start: V2,
    heading: Option<f64>,
    pieces: &[TrackPiece],
    solid: TrackSide,
    facets: Facets,
) -> Result<TrackPath, TrackFault> {
    if !(start.0.is_finite() && start.1.is_finite()) {
        return Err(TrackFault::NotFinite(None, "start"));
    }
    if heading.is_some_and(|h| !h.is_finite()) {
        return Err(TrackFault::NotFinite(None, "heading"));
    }
    if pieces.is_empty() {
        return Err(TrackFault::Empty);
    }
    let mut at = At {
        p: DVec2::from(start),
        heading,
    };
    let mut path = TrackPath {
        points: vec![start],
        edge_piece: Vec::new(),
        pieces: Vec::new(),
    };
    for (k, piece) in pieces.iter().enumerate() {
        let walked = match *piece {
            TrackPiece::Line { to } => line(&mut at, k, to, &mut path)?,
            TrackPiece::Arc { center, sweep } => {
                finite(k, &[center.0, center.1], "center")?;
                finite(k, &[sweep], "sweep")?;
                arc(
                    &mut at,
                    k,
                    DVec2::from(center),
                    sweep,
                    (solid, facets),
                    &mut path,
                )?
            }
            TrackPiece::Turn { radius, angle } => {
                finite(k, &[radius], "radius")?;
                finite(k, &[angle], "angle")?;
                let h = at.heading.ok_or(TrackFault::NoHeading(k))?;
                if radius <= 0.0 {
                    return Err(TrackFault::Radius(k, radius));
                }
                // The center is a quarter turn from the heading, to the side the piece turns.
                let side = if angle >= 0.0 { FRAC_PI_2 } else { -FRAC_PI_2 };
                let center = at.p + DVec2::from_angle(h + side) * radius;
                arc(&mut at, k, center, angle, (solid, facets), &mut path)?
            }
        };
        path.pieces.push(walked);
        if path.points.len() > MAX_TRACK_POINTS {
            return Err(TrackFault::TooManyPoints(path.points.len()));
        }
    }
    Ok(path)
}

fn finite(k: usize, values: &[f64], what: &'static str) -> Result<(), TrackFault> {
    if values.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(TrackFault::NotFinite(Some(k), what))
    }
}

fn line(at: &mut At, k: usize, to: V2, path: &mut TrackPath) -> Result<Walked, TrackFault> {
    finite(k, &[to.0, to.1], "to")?;
    let (from, to_v) = (at.p, DVec2::from(to));
    if from == to_v {
        return Err(TrackFault::ZeroLength(k));
    }
    at.heading = Some((to_v - from).to_angle());
    at.p = to_v;
    path.points.push(to);
    path.edge_piece.push(k);
    Ok(Walked::Line {
        from: from.into(),
        to,
    })
}

/// An arc piece about `center` from the walker's place, turning `sweep` rad (positive
/// counter-clockwise). Its facet vertices lie at 2 R / (1 + cos(a / 2)) as an `Arc`'s do
/// (`curves::arc_points`: the chords straddle the circle), but its end vertex lies on the circle,
/// where the next piece starts.
fn arc(
    at: &mut At,
    k: usize,
    center: DVec2,
    sweep: f64,
    (solid, facets): (TrackSide, Facets),
    path: &mut TrackPath,
) -> Result<Walked, TrackFault> {
    let radius = (at.p - center).length();
    if radius == 0.0 || sweep == 0.0 {
        return Err(TrackFault::ZeroLength(k));
    }
    if sweep.abs() >= TAU {
        return Err(TrackFault::WholeTurn(k, sweep));
    }
    let n = match facets {
        Facets::Engine(e) => {
            let n = curves::arc_facets(radius, sweep.abs(), curves::chord_error(radius, e));
            if n > curves::MAX_ARC_FACETS {
                return Err(TrackFault::TooManyFacets(k));
            }
            n
        }
        Facets::Step(step) => ((sweep.abs() / step).ceil() as usize).clamp(1, 720),
    };
    let a0 = (at.p - center).to_angle();
    let a = sweep / n as f64;
    let rv = 2.0 * radius / (1.0 + (a / 2.0).cos());
    for j in 1..=n {
        let r = if j == n { radius } else { rv };
        let p = center + DVec2::from_angle(a0 + a * j as f64) * r;
        path.points.push(p.into());
        path.edge_piece.push(k);
    }
    let a1 = a0 + sweep;
    at.p = center + DVec2::from_angle(a1) * radius;
    // The tangent at the end: a quarter turn from the radius, the way the piece turns.
    at.heading = Some(a1 + sweep.signum() * FRAC_PI_2);
    // Ridden on the concave side when the ground lies away from the center: turning left with
    // the ground on the right (a loop drawn counter-clockwise), or right with it on the left.
    let inside = (sweep > 0.0) == (solid == TrackSide::Right);
    let (start, end) = if sweep > 0.0 { (a0, a1) } else { (a1, a0) };
    Ok(Walked::Arc {
        center: center.into(),
        radius,
        start,
        end,
        inside,
    })
}

/// The first place where the track crosses, touches or folds back on itself, as the pieces
/// the two edges belong to and a point near it; None for a track that does not. Edges are
/// compared only where their boxes overlap in x (sweep and prune), so a track of many facets
/// is tested in about n log n.
pub fn crossing(path: &TrackPath) -> Option<TrackFault> {
    let p = &path.points;
    let edges = p.len().saturating_sub(1);
    let lo = |k: usize| p[k].0.min(p[k + 1].0);
    let hi = |k: usize| p[k].0.max(p[k + 1].0);
    let mut order: Vec<usize> = (0..edges).collect();
    order.sort_by(|&a, &b| lo(a).total_cmp(&lo(b)));
    let mut first: Option<(usize, usize, bool)> = None;
    for (n, &i) in order.iter().enumerate() {
        for &j in &order[n + 1..] {
            if lo(j) > hi(i) {
                break;
            }
            let (i, j) = (i.min(j), i.max(j));
            let next = j == i + 1;
            let fault = if next {
                curves::polyline_fault(&p[i..=j + 1], false).is_some()
            } else {
                curves::segments_meet(p[i], p[i + 1], p[j], p[j + 1])
            };
            if fault && first.is_none_or(|f| (i, j) < (f.0, f.1)) {
                first = Some((i, j, next));
            }
        }
    }
    first.map(|(i, j, next)| {
        let (a, b) = (path.edge_piece[i], path.edge_piece[j]);
        if next {
            TrackFault::FoldsBack(a, b, p[j])
        } else {
            TrackFault::Crossing(a, b, p[j])
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The n15 ramp, floor and loop: a quarter circle R = 2 about (0, 2) from (-2, 2), a floor
    /// to (1, 0), a loop R = 0.6 about (1, 0.6) turning 3 pi / 2.
    fn ramp_loop() -> Vec<TrackPiece> {
        vec![
            TrackPiece::Arc {
                center: (0.0, 2.0),
                sweep: PI / 2.0,
            },
            TrackPiece::Line { to: (1.0, 0.0) },
            TrackPiece::Arc {
                center: (1.0, 0.6),
                sweep: 1.5 * PI,
            },
        ]
    }

    #[test]
    fn the_ramp_floor_and_loop_walk_to_their_circles() {
        let path = walk(
            (-2.0, 2.0),
            None,
            &ramp_loop(),
            TrackSide::Right,
            Facets::Engine(None),
        )
        .unwrap();
        // The joints lie on the circles exactly: the ramp ends at (0, 0), the loop at its
        // angle pi, (0.4, 0.6).
        let ramp_end = path.edge_piece.iter().position(|&k| k == 1).unwrap();
        let q = path.points[ramp_end];
        assert!(q.0.abs() < 1e-12 && q.1.abs() < 1e-12, "{q:?}");
        let last = *path.points.last().unwrap();
        assert!((last.0 - 0.4).abs() < 1e-12 && (last.1 - 0.6).abs() < 1e-12);
        // Both arcs ridden inside (turning left, ground on the right).
        let arcs: Vec<_> = path
            .pieces
            .iter()
            .filter_map(|w| match w {
                Walked::Arc {
                    inside, start, end, ..
                } => Some((*inside, *start, *end)),
                _ => None,
            })
            .collect();
        assert_eq!(arcs.len(), 2);
        assert!(arcs.iter().all(|a| a.0));
        assert!((arcs[0].1 - PI).abs() < 1e-12 && (arcs[0].2 - 1.5 * PI).abs() < 1e-12);
        assert_eq!(crossing(&path), None);
    }

    #[test]
    fn a_turn_follows_the_heading_and_a_hump_is_ridden_outside() {
        // Heading east, turning right by a quarter turn, R = 1: the center 1 below the start,
        // the end at (1, -1); a right turn with the ground on the right is a hump.
        let path = walk(
            (0.0, 0.0),
            Some(0.0),
            &[TrackPiece::Turn {
                radius: 1.0,
                angle: -PI / 2.0,
            }],
            TrackSide::Right,
            Facets::Step(0.1),
        )
        .unwrap();
        let end = *path.points.last().unwrap();
        assert!((end.0 - 1.0).abs() < 1e-12 && (end.1 + 1.0).abs() < 1e-12);
        match &path.pieces[0] {
            Walked::Arc { center, inside, .. } => {
                assert!(!inside);
                assert!(center.0.abs() < 1e-12 && (center.1 + 1.0).abs() < 1e-12);
            }
            w => panic!("{w:?}"),
        }
    }

    #[test]
    fn faults_name_their_pieces() {
        let w = |pieces: &[TrackPiece]| {
            walk(
                (0.0, 0.0),
                None,
                pieces,
                TrackSide::Right,
                Facets::Step(0.1),
            )
        };
        assert_eq!(w(&[]), Err(TrackFault::Empty));
        let zero = [
            TrackPiece::Line { to: (1.0, 0.0) },
            TrackPiece::Line { to: (1.0, 0.0) },
        ];
        assert_eq!(w(&zero), Err(TrackFault::ZeroLength(1)));
        let turn = [TrackPiece::Turn {
            radius: 1.0,
            angle: 1.0,
        }];
        assert_eq!(w(&turn), Err(TrackFault::NoHeading(0)));
        let nan = [TrackPiece::Arc {
            center: (f64::NAN, 0.0),
            sweep: 1.0,
        }];
        assert_eq!(w(&nan), Err(TrackFault::NotFinite(Some(0), "center")));
        // A Z folded into a cross: east 2, up-left, then east again through the first line.
        let cross = [
            TrackPiece::Line { to: (2.0, 0.0) },
            TrackPiece::Line { to: (1.0, 1.0) },
            TrackPiece::Line { to: (1.0, -1.0) },
        ];
        let path = w(&cross).unwrap();
        assert!(matches!(
            crossing(&path),
            Some(TrackFault::Crossing(0, 2, _))
        ));
        // Back along itself.
        let back = [
            TrackPiece::Line { to: (2.0, 0.0) },
            TrackPiece::Line { to: (1.0, 0.0) },
        ];
        let path = w(&back).unwrap();
        assert!(matches!(
            crossing(&path),
            Some(TrackFault::FoldsBack(0, 1, _))
        ));
    }
}
