//! STUB, to be replaced by the method's implementation (not registered as done).
use super::*;
struct Stub;
struct P;
impl Prepared for P {
    fn tile(&self, _t: &Tile) -> TileResult {
        TileResult::Bounds(TileBounds::full())
    }
}
static INFO: MethodInfo = MethodInfo {
    id: "gdam2010",
    source: "STUB",
    reconstruction: false,
    dims: &[],
    outputs: Outputs { tile_reject: false, lens: false, time: false, depth: false, per_sample: false },
};
impl Method for Stub {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, _t: &Triangle) -> Box<dyn Prepared> {
        Box::new(P)
    }
}
pub static METHOD: &dyn Method = &Stub;
