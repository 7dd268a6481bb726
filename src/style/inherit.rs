//! Style inheritance from one layer to the next (seed 002, §3.2): around each
//! styled line of layer i lies a band of half-width R/2; a line of layer i+1 that
//! lies inside a style's bands for at least the "hit factor" of its length takes
//! that style. The hit factor is what keeps lines that merely cross a band (the
//! paper's lines 3 and 4) from inheriting.

use super::band::Bands;
use super::StyleId;

/// The previous layer's styled tracks, indexed once so that every track of the
/// next layer can be tested against them cheaply.
///
/// Semantics: per-style union. The band of a style is the union of the bands
/// around *all* previous tracks of that style, so a new track that runs along two
/// consecutive styled tracks (end to end) is covered by both together. Tracks of
/// the default style 0 do not propagate and are left out.
///
/// Complexity: [`Inheritance::new`] is O(P) in the previous layer's styled points
/// (a uniform grid, cell ≈ the half-width, memory O(P) for any input);
/// [`Inheritance::style_of`] costs, per segment of the new track, the grid cells
/// it crosses plus the previous segments found in them. For a layer of tracks
/// that each lie near a bounded number of previous segments this is O(Q) in the
/// new track's points, so a whole layer is near-linear in points rather than
/// O(P·Q).
#[derive(Debug)]
pub struct Inheritance {
    bands: Bands,
    hit: f64,
}

impl Inheritance {
    /// Indexes the previous layer's tracks and their styles, with band half-width
    /// `half_width` (the paper's R/2, mm) and hit factor `hit` (e.g. 0.99).
    ///
    /// A NaN or negative half-width is no band (nothing inherits); a NaN hit factor
    /// or one above 1 lets nothing inherit.
    pub fn new(prev: &[(&[[f64; 2]], StyleId)], half_width: f64, hit: f64) -> Self {
        let styled = prev.iter().filter(|(_, s)| *s != 0).map(|&(l, s)| (l, s));
        Inheritance {
            bands: Bands::new(styled, false, half_width),
            hit,
        }
    }

    /// For each style whose bands the track enters, the fraction (0..=1) of the
    /// track's length inside the union of that style's bands; sorted by style.
    /// Empty for a zero-length track.
    pub fn fractions(&self, track: &[[f64; 2]]) -> Vec<(StyleId, f64)> {
        let cov = self.bands.coverage(track);
        cov.covered
            .iter()
            .map(|&(s, _)| (s, cov.fraction(s)))
            .filter(|&(_, f)| f > 0.0)
            .collect()
    }

    /// The style the track inherits, if any: among the styles covering at least
    /// the hit factor of its length (and more than nothing, so a hit factor ≤ 0
    /// does not style tracks far from every band), the one covering the largest
    /// fraction; equal fractions go to the lower style id.
    pub fn style_of(&self, track: &[[f64; 2]]) -> Option<StyleId> {
        let mut best: Option<(StyleId, f64)> = None;
        // Ascending ids and a strict `>`: ties keep the lower id.
        for (s, f) in self.fractions(track) {
            if f >= self.hit && best.is_none_or(|(_, b)| f > b) {
                best = Some((s, f));
            }
        }
        best.map(|(s, _)| s)
    }
}

/// The style a track of layer i+1 inherits from the styled tracks `prev` of layer
/// i (see [`Inheritance`] for the band, the per-style union and ties), or `None`.
///
/// Builds the index for this one call: to style a whole layer, build one
/// [`Inheritance`] and call [`Inheritance::style_of`] per track.
pub fn inherit(
    prev: &[(&[[f64; 2]], StyleId)],
    track: &[[f64; 2]],
    half_width: f64,
    hit: f64,
) -> Option<StyleId> {
    Inheritance::new(prev, half_width, hit).style_of(track)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LINE: &[[f64; 2]] = &[[0.0, 0.0], [10.0, 0.0]];

    #[test]
    fn default_style_does_not_propagate() {
        assert_eq!(
            inherit(&[(LINE, 0)], &[[1.0, 0.1], [9.0, 0.1]], 0.5, 0.99),
            None
        );
        assert_eq!(
            inherit(&[(LINE, 3)], &[[1.0, 0.1], [9.0, 0.1]], 0.5, 0.99),
            Some(3)
        );
    }

    #[test]
    fn largest_fraction_wins_then_lower_id() {
        let other: &[[f64; 2]] = &[[0.0, 0.8], [5.0, 0.8]];
        // y = 0.4 from x = 1 to 9: style 7 (y = 0, band 0.6) covers all of it,
        // style 2 (y = 0.8) x ≤ 5 + √(0.6² − 0.4²): both pass the hit factor 0.4.
        let track = [[1.0, 0.4], [9.0, 0.4]];
        let prev = [(other, 2), (LINE, 7)];
        let fr = Inheritance::new(&prev, 0.6, 0.4).fractions(&track);
        let cap = (0.36f64 - 0.16).sqrt();
        assert_eq!(fr.len(), 2);
        assert!(
            fr[0].0 == 2 && (fr[0].1 - (4.0 + cap) / 8.0).abs() < 1e-12,
            "{fr:?}"
        );
        assert_eq!(fr[1], (7, 1.0));
        assert_eq!(inherit(&prev, &track, 0.6, 0.4), Some(7));
        // The same line under two styles: equal fractions, the lower id wins.
        assert_eq!(inherit(&[(LINE, 9), (LINE, 4)], &track, 0.6, 0.99), Some(4));
    }

    #[test]
    fn per_style_union_joins_consecutive_tracks() {
        let a: &[[f64; 2]] = &[[0.0, 0.0], [5.0, 0.0]];
        let b: &[[f64; 2]] = &[[5.0, 0.0], [10.0, 0.0]];
        let track = [[1.0, 0.2], [9.0, 0.2]];
        assert_eq!(inherit(&[(a, 5), (b, 5)], &track, 0.5, 0.99), Some(5));
        // Split between two styles, neither reaches the hit factor.
        assert_eq!(inherit(&[(a, 5), (b, 6)], &track, 0.5, 0.99), None);
    }

    #[test]
    fn zero_hit_needs_some_overlap() {
        assert_eq!(
            inherit(&[(LINE, 3)], &[[0.0, 5.0], [9.0, 5.0]], 0.5, 0.0),
            None
        );
    }

    #[test]
    fn zero_length_tracks_do_not_inherit() {
        assert_eq!(inherit(&[(LINE, 3)], &[[1.0, 0.0]], 0.5, 0.5), None);
        assert_eq!(
            inherit(&[(LINE, 3)], &[[1.0, 0.0], [1.0, 0.0]], 0.5, 0.0),
            None
        );
        assert_eq!(inherit(&[(LINE, 3)], &[], 0.5, 0.0), None);
    }
}
