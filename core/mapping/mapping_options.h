// Options of model-assisted mapping (Ozog et al., Section 3): one struct for
// the GUI panel, the CLI flags and the project file; Check() refuses invalid
// values naming the field. Lengths in metres, areas in square metres.
#pragma once

namespace hull {

struct MappingOptions {
  // ---- Algorithm 1: shapes per keyframe -------------------------------------
  // Features whose |deviation| from the CAD surface exceeds tau are clustered
  // (line 6). 0 (the paper's preferred setting) clusters every feature, so
  // the shapes cover everything seen; 0.06 m gives fewer false positives.
  double tau = 0.0;
  // Alpha-shape radius: a Delaunay triangle is kept when its circumradius is
  // at most alpha (CGAL's Alpha_shape_2 takes alpha squared). Larger values
  // bridge wider gaps between features; smaller ones leave holes.
  double alpha = 0.12;
  // DBSCAN over the points (x, y, |d|), x and y in the top-camera frame:
  // neighbourhood radius ...
  double dbscan_eps = 0.10;
  // ... and the number of points (the point itself included) within eps that
  // makes a core point.
  int dbscan_min_points = 3;
  // Hysteresis (as in Canny's edge detector): with tau above it, features
  // whose |deviation| exceeds this lower level are clustered too, and a
  // cluster is kept only when it holds a feature above tau (a seed). tau
  // then decides which clusters become shapes (those reaching above it)
  // instead of cutting each shape down to its part above tau: a narrow lump
  // whose top exceeds tau gets a shape over its footprint down to this
  // level, while a cluster with no feature above tau still forms none. The
  // level must stand above the hull's noise (the adjusted clean-hull
  // features' 99th percentile is 1.2-1.5 cm), or clusters grow over the hull
  // around an object (0 and 0.005 m made false objects or changes). A value
  // >= tau turns it off (the paper's Algorithm 1, each feature cut at tau);
  // at tau = 0 it has no effect. docs/mapping.md, "Algorithm 1".
  double shape_grow_height = 0.015;
  // With hysteresis: a keyframe's cluster is also kept when it holds a
  // landmark that a seeded cluster of another keyframe holds (the seed is a
  // property of the structure, not of the views that happened to see the
  // feature above tau). docs/mapping.md, "Seeds across views".
  bool shape_seed_across_views = true;

  // ---- Algorithm 2: fusion into the mesh -------------------------------------
  // Only model vertices within this distance of the top camera are fused
  // (the paper's nearby_vertices(), 5 m).
  double fusion_radius = 5.0;
  // How a vertex's hits combine (FusionRule, shape_fusion.h): true keeps
  // peaks (the vertex rises to the height fusion_support hits reach, the
  // mean of those within fusion_peak_band below it); false is the paper's
  // eq. 15 (the mean of every hit), which flattens narrow peaks.
  bool fusion_keep_peaks = true;
  // Hits that must reach a height before a vertex rises to it (so one wrong
  // match cannot raise a peak); a vertex with fewer hits stays on the CAD.
  int fusion_support = 2;
  // Hits within this band (m) below the supported height are averaged.
  double fusion_peak_band = 0.005;
  // The line a vertex is fused along: true (the default) its outward
  // normal, after moving the vertex nearest each supported feature under it
  // (every view then meets a narrow peak over the same vertex, at the
  // feature); false the camera's ray through it (the paper's; parallax
  // spreads a narrow peak over several vertices). docs/mapping.md, "Keeping
  // peaks".
  bool fusion_along_normal = true;
  // A lump's apex beyond its highest feature (with the fusion along normals
  // and keep_peaks; peak_fit.h): around each local maximum of the supported
  // features a quadric height model is fitted to the features within a few
  // centimetres; an apex that passes every test (concave, inside the
  // features, small residuals, at most 3.5 cm above the features, and the
  // same without any one feature: the lowest of those fits is taken) raises
  // the fused vertex under it where the fusion moved that vertex. On by
  // default: on every measured survey it moved model maxima toward the
  // truth and none above it (docs/mapping.md, "Fitting a lump's apex").
  bool peak_fit = true;
  // Target edge length of the isotropic remeshing where shapes depart from
  // the CAD surface.
  double refine_edge = 0.03;
  // A clustered feature departs from the CAD surface when its |deviation|
  // exceeds this and two more of its cluster within alpha do too (one noisy
  // feature alone refines nothing).
  double refine_threshold = 0.01;
  // The refined region is where departing features are seen on the CAD,
  // grown by this margin plus alpha.
  double refine_margin = 0.10;

  // ---- Uncertainty -------------------------------------------------------------
  // A vertex's deviation is significant when |deviation| > significance_k
  // times its sigma (the sigma_h of the nearest adjusted landmark; M3C2's
  // level of detection at 95 % for k = 1.96).
  double significance_k = 1.96;

  // ---- Detected objects --------------------------------------------------------
  // A detected object is a connected region of the fused model whose
  // deviation exceeds object_min_height (h_min) ...
  double object_min_height = 0.03;
  // ... over at least this footprint area, ...
  double object_min_area = 0.01;
  // ... or, over a smaller footprint, held up by at least this many of the
  // run's shaped features (vertices of Algorithm 1's shapes) lying over it
  // and standing above h_min, ...
  int object_min_features = 3;
  // ... that the shapes of at least this many keyframes hold: a tall narrow
  // lump whose footprint above h_min is below object_min_area is still an
  // object when several features seen from several views measured it, while
  // a blip raised by one or two features is not. 0 keeps the area test
  // alone. The default since Algorithm 1's hysteresis (shape_grow_height):
  // with it, 3 found more objects and no false object or change on every
  // measured run at tau = 0 and 0.06 m (docs/mapping.md, "Objects").
  int object_min_views = 2;

  // ---- Fouling assessment --------------------------------------------------------
  // Stations along the hull's length (zones are station x {bottom, port,
  // starboard}); station 0 is at the bow.
  int stations = 20;
  // A surface is bottom where its outward normal is within this angle
  // (degrees) of straight down; surfaces within it of straight up (decks)
  // belong to no zone.
  double bottom_angle_deg = 45.0;
  // Spacing of the samples of the CAD surface that measure the inspected
  // area (a sample is inspected when a keyframe's top camera sees it).
  double inspection_spacing = 0.10;
  // A camera inspects the surface up to this distance.
  double inspection_range = 4.0;

  // ---- Execution -------------------------------------------------------------------
  // Worker threads (TBB); 0: all cores. Results do not depend on it.
  int num_threads = 0;

  // Throws OptionError naming the first invalid field and why.
  void Check() const;
  // alpha as CGAL takes it (a squared radius).
  double CgalAlpha() const { return alpha * alpha; }
};

}  // namespace hull
