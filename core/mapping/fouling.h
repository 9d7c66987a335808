// The fouling assessment per hull zone (stations x {bottom, port,
// starboard}): how much of the zone the survey inspected, how much of that
// the detected objects cover, and the IMO biofouling rating of MEPC.378(80)
// (2023 Biofouling Guidelines) from that cover: 2 light macrofouling for
// 1-15 %, 3 medium for more than 15 up to 40 %, 4 heavy above 40 %. Below
// 1 % the rating is "0-1": ratings 0 (clean) and 1 (slime, microfouling)
// differ by what geometry cannot see. A zone no camera saw is
// "uninspected", never clean.
#pragma once

#include <string>
#include <vector>

#include "mapping/detected_objects.h"
#include "mapping/hull_zones.h"
#include "mapping/inspection.h"

namespace hull {

enum class FoulingRating {
  kUninspected,  // no part of the zone was seen
  kZeroToOne,    // < 1 % macrofouling cover: 0 or 1, not told apart by geometry
  kLight,        // 2: 1 % to 15 %
  kMedium,       // 3: above 15 % up to 40 %
  kHeavy,        // 4: above 40 %
};
const char* FoulingRatingName(FoulingRating r);  // "uninspected", "0-1", "2", "3", "4"

// The rating of an inspected zone from its macrofouling cover (percent of
// the inspected area).
FoulingRating RateCover(double cover_percent);

struct ZoneAssessment {
  int station = 0;  // 0 at the bow
  HullSide side = HullSide::kBottom;
  double from_bow = 0, to_bow = 0;  // the station's extent (m from the bow)
  double hull_area = 0;             // CAD area of the zone (m^2)
  double inspected_area = 0;        // the part a camera saw (m^2)
  double covered_area = 0;          // the part detected objects cover (m^2)
  double cover_percent = 0;         // covered / inspected (0 when uninspected)
  int objects = 0;                  // detected objects with their centroid here
  double mean_height = 0;           // m, area-weighted over the covered area (0 if none)
  double max_height = 0;            // m
  FoulingRating rating = FoulingRating::kUninspected;
  std::string note;  // what the rating means and what it cannot tell
};

// One entry per zone with hull area, in zone order (station, then side).
std::vector<ZoneAssessment> AssessFouling(const HullFrame& hull, const InspectionCoverage& inspection,
                                          const ObjectDetection& objects);

}  // namespace hull
