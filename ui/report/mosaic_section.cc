// The report's photomosaic section: the fused model textured from the camera
// images ('hullinspect-cli mosaic', docs/mosaic.md), drawn from its
// per-vertex colour (mosaic.ply) from every side the heatmaps show.
#include "ui/report/report_blocks.h"
#include "ui/report/report_sections.h"

namespace hull::report {

void PlanMosaicFigures(const ReportInputs& in, std::vector<FigureRef>& figures) {
  if (!in.mosaic || !in.mapping) return;
  for (const HullView v : HeatmapViews(figures)) {
    figures.push_back(ViewFigure(
        FigureKind::kMosaic, "mosaic", v, "Photomosaic, " + ViewWords(v),
        "The fused model coloured by the photomosaic's per-vertex colour: the hull's albedo estimated from the "
        "camera images (each face from its best view, gains normalised, seams feathered), seen " +
            ViewWords(v) +
            "; grey where no image saw the surface. The vertex colours are coarser than the mosaic's texture "
            "(mosaic.obj with its atlas, in the application). Top: the whole hull; bottom: the surveyed stretch."));
  }
}

Section MosaicSection(const ReportInputs& in, const std::vector<FigureRef>& figures) {
  Section s{"photomosaic", "Photomosaic", true, {}};
  if (!in.mosaic) {
    s.blocks.push_back(Paragraph(
        "No photomosaic was made of these results ('hullinspect-cli mosaic RESULTS' writes one into RESULTS/mosaic; "
        "the report reads it from there)."));
    return s;
  }
  std::vector<std::pair<std::string, std::string>> facts;
  if (!in.mosaic_path.empty()) facts.emplace_back("Mosaic", in.mosaic_path);
  facts.emplace_back("Triangles", Count(static_cast<long long>(in.mosaic->num_faces())));
  facts.emplace_back("Vertices", Count(static_cast<long long>(in.mosaic->num_vertices())));
  s.blocks.push_back(Facts(std::move(facts)));
  s.blocks.push_back(Paragraph(
      "The fused model textured from the camera images: every face takes the view that resolves it best (near and "
      "frontal, not occluded), neighbouring faces keep the same view unless another is much better, each image's "
      "gain is normalised against the rig's photometric model and the seams are feathered. The textured model "
      "(mosaic.obj with its atlas) opens in the application (File ▸ Open photomosaic…) and in other 3-D viewers; the "
      "figures draw its per-vertex colour."));
  if (!in.mapping) {
    s.blocks.push_back(Paragraph("Mapping's results are missing, so the mosaic is not drawn."));
    return s;
  }
  for (const FigureRef& f : figures) {
    if (f.kind == FigureKind::kMosaic) s.blocks.push_back(FigureBlock(f));
  }
  return s;
}

}  // namespace hull::report
