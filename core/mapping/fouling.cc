#include "mapping/fouling.h"

#include <algorithm>
#include <cmath>

namespace hull {

const char* FoulingRatingName(FoulingRating r) {
  switch (r) {
    case FoulingRating::kUninspected:
      return "uninspected";
    case FoulingRating::kZeroToOne:
      return "0-1";
    case FoulingRating::kLight:
      return "2";
    case FoulingRating::kMedium:
      return "3";
    case FoulingRating::kHeavy:
      return "4";
  }
  return "?";
}

FoulingRating RateCover(double p) {
  if (p < 1.0) return FoulingRating::kZeroToOne;
  if (p <= 15.0) return FoulingRating::kLight;
  if (p <= 40.0) return FoulingRating::kMedium;
  return FoulingRating::kHeavy;
}

std::vector<ZoneAssessment> AssessFouling(const HullFrame& hull, const InspectionCoverage& inspection,
                                          const ObjectDetection& objects) {
  std::vector<ZoneAssessment> out;
  for (int station = 0; station < hull.stations(); ++station) {
    for (const HullSide side : {HullSide::kBottom, HullSide::kPort, HullSide::kStarboard}) {
      const std::size_t z = static_cast<std::size_t>(HullFrame::ZoneIndex(station, side));
      if (!(inspection.hull_area[z] > 0)) continue;
      ZoneAssessment a;
      a.station = station;
      a.side = side;
      a.from_bow = station * hull.station_length();
      a.to_bow = (station + 1) * hull.station_length();
      a.hull_area = inspection.hull_area[z];
      a.inspected_area = inspection.inspected_area[z];
      a.covered_area = objects.zone_covered_area[z];
      a.objects = objects.zone_objects[z];
      a.max_height = objects.zone_max_height[z];
      if (a.covered_area > 0) a.mean_height = objects.zone_height_integral[z] / a.covered_area;
      if (!(a.inspected_area > 0)) {
        a.rating = FoulingRating::kUninspected;
        a.note = "not seen by the survey: no rating (not clean)";
      } else {
        a.cover_percent = std::min(100.0, 100.0 * a.covered_area / a.inspected_area);
        a.rating = RateCover(a.cover_percent);
        switch (a.rating) {
          case FoulingRating::kZeroToOne:
            a.note =
                "no macrofouling detected (< 1 % cover); slime and microfouling (ratings 0 and 1) are "
                "invisible to geometry";
            break;
          case FoulingRating::kLight:
            a.note = "light macrofouling (1-15 % cover)";
            break;
          case FoulingRating::kMedium:
            a.note = "medium macrofouling (16-40 % cover)";
            break;
          default:
            a.note = "heavy macrofouling (41-100 % cover)";
            break;
        }
        const double seen = a.inspected_area / a.hull_area;
        if (seen < 0.5) {
          a.note += "; only " + std::to_string(std::lround(100 * seen)) + " % of the zone inspected";
        }
      }
      out.push_back(std::move(a));
    }
  }
  return out;
}

}  // namespace hull
