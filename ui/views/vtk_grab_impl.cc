#include "ui/views/vtk_grab_impl.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <cstring>

namespace hull::ui {

QImage GrabRenderWindow(vtkRenderWindow* window) {
  vtkNew<vtkWindowToImageFilter> filter;
  filter->SetInput(window);
  filter->SetInputBufferTypeToRGB();
  filter->ReadFrontBufferOff();
  filter->ShouldRerenderOn();
  filter->Update();
  vtkImageData* image = filter->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] <= 0 || dims[1] <= 0) return {};
  auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  QImage out(dims[0], dims[1], QImage::Format_RGB888);
  // VTK's rows run bottom-up.
  for (int y = 0; y < dims[1]; ++y) {
    std::memcpy(out.scanLine(dims[1] - 1 - y), pixels + static_cast<std::size_t>(y) * dims[0] * 3,
                static_cast<std::size_t>(dims[0]) * 3);
  }
  return out;
}

}  // namespace hull::ui
