//! Methods as the library holds them: [`MethodRef`], a shared handle that a built-in
//! method (a `&'static` in the registry) and a user's own bound (any value
//! implementing [`Method`]) both become.

use super::{Method, MethodInfo, Prepared};
use crate::model::Triangle;
use std::sync::Arc;

/// A culling method held by the gate, the search, the tightness run, ...
pub type MethodRef = Arc<dyn Method>;

/// A registry entry is a method too.
impl<M: Method + ?Sized> Method for &'static M {
    fn info(&self) -> &'static MethodInfo {
        (**self).info()
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        (**self).setup(tri)
    }
}

/// The handle of a registry entry.
pub fn shared(m: &'static dyn Method) -> MethodRef {
    Arc::new(m)
}

/// The handles of registry entries.
pub fn shared_all(ms: impl IntoIterator<Item = &'static dyn Method>) -> Vec<MethodRef> {
    ms.into_iter().map(shared).collect()
}
