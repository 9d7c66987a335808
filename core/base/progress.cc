#include "base/progress.h"

#include "base/error.h"

namespace hull {

void Progress::ThrowIfCancelled() const {
  if (Cancelled()) throw hull::Cancelled();
}

}  // namespace hull
