//! The counts of one triangle ([`TriCounts`]) and their sums over a setting's triangles
//! ([`Sums`]): integers, the same in any order, so at any thread count.

use super::scene::Setting;
use super::types::{CertifiedRow, Counts, SettingSummary, Work};

/// One triangle's contribution.
#[derive(Default)]
pub(super) struct TriCounts {
    pub(super) whole_screen: bool,
    pub(super) off_screen: bool,
    pub(super) classified: u64,
    pub(super) covered: u64,
    pub(super) boundary: u64,
    pub(super) exact: u64,
    /// [tile index][method index]
    pub(super) counts: Vec<Vec<Counts>>,
    /// [tile index][method index]
    pub(super) work: Vec<Vec<Work>>,
    /// [tile index]: (tested, covered)
    pub(super) ceiling: Vec<(u64, u64)>,
    pub(super) certified: Vec<CertifiedRow>,
    pub(super) disabled: Vec<bool>,
}

impl TriCounts {
    /// Zero, for `nt` tile sizes and `nm` methods (the buffers kept from triangle to
    /// triangle).
    pub(super) fn reset(&mut self, nt: usize, nm: usize) {
        self.whole_screen = false;
        self.off_screen = false;
        (self.classified, self.covered, self.boundary, self.exact) = (0, 0, 0, 0);
        self.counts.resize_with(nt, Vec::new);
        self.counts.iter_mut().for_each(|c| {
            c.clear();
            c.resize(nm, Counts::default());
        });
        self.work.resize_with(nt, Vec::new);
        self.work.iter_mut().for_each(|w| {
            w.clear();
            w.resize(nm, Work::default());
        });
        self.ceiling.clear();
        self.ceiling.resize(nt, (0, 0));
        self.certified.clear();
        self.disabled.clear();
        self.disabled.resize(nm, false);
    }
}

/// The sums over a setting's triangles (integers: the same in any order, so at any
/// thread count).
pub(super) struct Sums {
    pub(super) summary: SettingSummary,
    /// [tile index][method index]
    pub(super) counts: Vec<Vec<Counts>>,
    pub(super) work: Vec<Vec<Work>>,
    pub(super) ceiling: Vec<(u64, u64)>,
    pub(super) disabled: Vec<u64>,
    /// [tile index]
    pub(super) certified: Vec<CertifiedRow>,
}

impl Sums {
    pub(super) fn new(setting: Setting, tiles: &[u32], nm: usize) -> Self {
        let nt = tiles.len();
        Sums {
            summary: SettingSummary { setting, ..Default::default() },
            counts: vec![vec![Counts::default(); nm]; nt],
            work: vec![vec![Work::default(); nm]; nt],
            ceiling: vec![(0, 0); nt],
            disabled: vec![0; nm],
            certified: tiles.iter().map(|&s| CertifiedRow { setting, tile: s, ..Default::default() }).collect(),
        }
    }
    /// One triangle's contribution added.
    pub(super) fn add(&mut self, r: &TriCounts, tiles: &[u32]) {
        let sum = &mut self.summary;
        sum.triangles += 1;
        sum.whole_screen += r.whole_screen as u64;
        sum.off_screen += r.off_screen as u64;
        sum.samples_classified += r.classified;
        sum.covered += r.covered;
        sum.boundary += r.boundary;
        sum.exact_fallbacks += r.exact;
        if r.off_screen {
            return;
        }
        self.add_tables(&r.counts, &r.work, &r.ceiling);
        for (d, &x) in self.disabled.iter_mut().zip(&r.disabled) {
            *d += x as u64;
        }
        for c in &r.certified {
            let ti = tiles.iter().position(|&s| s == c.tile).unwrap();
            self.certified[ti].add(c);
        }
    }
    /// Per tile size and method: counts and work added; per tile size: the ceiling's.
    fn add_tables(&mut self, counts: &[Vec<Counts>], work: &[Vec<Work>], ceiling: &[(u64, u64)]) {
        for ti in 0..self.counts.len() {
            for (acc, x) in self.counts[ti].iter_mut().zip(&counts[ti]) {
                acc.add(x);
            }
            for (acc, x) in self.work[ti].iter_mut().zip(&work[ti]) {
                acc.add(x);
            }
            self.ceiling[ti].0 += ceiling[ti].0;
            self.ceiling[ti].1 += ceiling[ti].1;
        }
    }
    /// Two partial sums added.
    pub(super) fn merge(mut self, o: Sums) -> Sums {
        let (a, b) = (&mut self.summary, &o.summary);
        a.triangles += b.triangles;
        a.whole_screen += b.whole_screen;
        a.off_screen += b.off_screen;
        a.samples_classified += b.samples_classified;
        a.covered += b.covered;
        a.boundary += b.boundary;
        a.exact_fallbacks += b.exact_fallbacks;
        self.add_tables(&o.counts, &o.work, &o.ceiling);
        for (acc, c) in self.certified.iter_mut().zip(&o.certified) {
            acc.add(c);
        }
        for (d, &x) in self.disabled.iter_mut().zip(&o.disabled) {
            *d += x;
        }
        self
    }
}

impl CertifiedRow {
    /// The counts of `c` added (the STE bounds are computed from the sums at the end).
    fn add(&mut self, c: &CertifiedRow) {
        self.tiles += c.tiles;
        self.undecided_tiles += c.undecided_tiles;
        self.covered += c.covered;
        self.tested_certified += c.tested_certified;
        self.tested_sample_box += c.tested_sample_box;
        self.boxes += c.boxes;
    }
}
