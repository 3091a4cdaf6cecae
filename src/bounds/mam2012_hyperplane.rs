//! STUB, to be replaced by the method's implementation (not registered as done).
use super::*;
struct Stub(&'static MethodInfo);
struct P;
impl Prepared for P {
    fn tile(&self, _t: &Tile) -> TileResult {
        TileResult::Bounds(TileBounds::full())
    }
}
static INFO: MethodInfo = MethodInfo {
    id: "mam2012-hyperplane",
    source: "STUB",
    reconstruction: false,
    dims: &[],
    outputs: Outputs { tile_reject: false, lens: false, time: false, depth: false, per_sample: false },
};
static INFO_PS: MethodInfo = MethodInfo { id: "mam2012-hyperplane-ps", ..INFO };
impl Method for Stub {
    fn info(&self) -> &'static MethodInfo {
        self.0
    }
    fn setup(&self, _t: &Triangle) -> Box<dyn Prepared> {
        Box::new(P)
    }
}
pub static METHOD: &dyn Method = &Stub(&INFO);
pub static METHOD_PS: &dyn Method = &Stub(&INFO_PS);
