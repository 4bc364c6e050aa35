//! The query-writing macro of the indices: an [`Index`](crate::index::Index) impl's
//! `closest_hit` and `any_hit` from two free query functions.

/// The [`Index`](crate::index::Index) methods `closest_hit` and `any_hit` of an index whose queries are the functions
/// `$closest` and `$any`, each called as `(view, geom, ray, stats)` with `view` the expression
/// `$view` of the index bound to `$this` (e.g. `|index| &index.tree()`).
macro_rules! ray_queries {
    ($closest:expr, $any:expr, |$this:ident| $view:expr) => {
        #[inline]
        fn closest_hit<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            ray: &$crate::geometry::Ray,
            stats: &mut S,
        ) -> Option<$crate::geometry::Hit> {
            let $this = self;
            $closest($view, geom, ray, stats)
        }

        #[inline]
        fn any_hit<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            ray: &$crate::geometry::Ray,
            stats: &mut S,
        ) -> bool {
            let $this = self;
            $any($view, geom, ray, stats)
        }
    };
}
pub(crate) use ray_queries;
