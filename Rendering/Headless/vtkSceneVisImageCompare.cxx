// Image measures and PNG files; see vtkSceneVisImageCompare.h.
#include "vtkSceneVisImageCompare.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace scenevis
{
namespace headless
{
namespace
{
/// The unsigned-char scalars of a 2-D image, or nullptr.
vtkUnsignedCharArray* Pixels(vtkImageData* image)
{
  if (!image || !image->GetPointData())
  {
    return nullptr;
  }
  return vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
}

bool IsBackground(const unsigned char* pixel, int components, const Rgb& background)
{
  for (int c = 0; c < std::min(components, 3); ++c)
  {
    if (pixel[c] != background[static_cast<std::size_t>(c)])
    {
      return false;
    }
  }
  return true;
}

} // namespace

std::string ImageDifference::Summary() const
{
  std::ostringstream text;
  if (!this->comparable)
  {
    text << "images not comparable: " << this->problem;
    return text.str();
  }
  text << this->width << "x" << this->height << "x" << this->channels << ": mean abs error "
       << this->meanAbsError << ", max error " << this->maxError << ", bad covered pixels "
       << this->badCoveredPixels << "/" << this->coveredPixels << " (" << this->coveredBadFraction
       << ")";
  return text.str();
}

ImageDifference CompareImages(
  vtkImageData* actual, vtkImageData* expected, Rgb background, int badPixelLevel)
{
  ImageDifference result;
  vtkUnsignedCharArray* a = Pixels(actual);
  vtkUnsignedCharArray* b = Pixels(expected);
  if (!a || !b)
  {
    result.problem = "an image is missing or does not have unsigned char scalars";
    return result;
  }
  int da[3];
  int db[3];
  actual->GetDimensions(da);
  expected->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1] || da[2] != 1 || db[2] != 1)
  {
    std::ostringstream text;
    text << "sizes differ: actual " << da[0] << "x" << da[1] << "x" << da[2] << ", expected "
         << db[0] << "x" << db[1] << "x" << db[2];
    result.problem = text.str();
    return result;
  }
  const int ca = a->GetNumberOfComponents();
  const int cb = b->GetNumberOfComponents();
  result.width = da[0];
  result.height = da[1];
  result.channels = std::min({ ca, cb, 3 });
  const std::size_t count = static_cast<std::size_t>(da[0]) * static_cast<std::size_t>(da[1]);
  if (static_cast<std::size_t>(a->GetNumberOfTuples()) != count ||
    static_cast<std::size_t>(b->GetNumberOfTuples()) != count)
  {
    result.problem = "pixel count does not match the dimensions";
    return result;
  }
  // Grey images (1-2 components) only compare channel 0; colour images compare RGB.
  if (ca < 3 || cb < 3)
  {
    result.channels = 1;
  }
  const unsigned char* pa = a->GetPointer(0);
  const unsigned char* pb = b->GetPointer(0);
  double sum = 0;
  for (std::size_t i = 0; i < count; ++i, pa += ca, pb += cb)
  {
    int pixelMax = 0;
    for (int c = 0; c < result.channels; ++c)
    {
      const int d = std::abs(int(pa[c]) - int(pb[c]));
      sum += d;
      pixelMax = std::max(pixelMax, d);
    }
    result.maxError = std::max(result.maxError, pixelMax);
    const bool covered = !IsBackground(pa, result.channels, background) ||
      !IsBackground(pb, result.channels, background);
    if (covered)
    {
      ++result.coveredPixels;
      if (pixelMax > badPixelLevel)
      {
        ++result.badCoveredPixels;
      }
    }
  }
  result.comparable = true;
  result.meanAbsError = count ? sum / (double(count) * result.channels) : 0.0;
  result.coveredBadFraction =
    result.coveredPixels ? double(result.badCoveredPixels) / double(result.coveredPixels) : 0.0;
  return result;
}

bool WithinThresholds(
  const ImageDifference& difference, const ImageThresholds& thresholds, std::string* why)
{
  std::ostringstream text;
  if (!difference.comparable)
  {
    text << difference.problem;
  }
  else
  {
    if (difference.meanAbsError > thresholds.maxMeanAbsError)
    {
      text << "mean abs error " << difference.meanAbsError << " > " << thresholds.maxMeanAbsError
           << "; ";
    }
    if (difference.coveredBadFraction > thresholds.maxCoveredBadFraction)
    {
      text << "bad covered fraction " << difference.coveredBadFraction << " > "
           << thresholds.maxCoveredBadFraction << "; ";
    }
    if (difference.maxError > thresholds.maxError)
    {
      text << "max error " << difference.maxError << " > " << thresholds.maxError << "; ";
    }
  }
  if (why)
  {
    *why = text.str();
  }
  return text.str().empty();
}

double CoveredFraction(vtkImageData* image, Rgb background)
{
  vtkUnsignedCharArray* pixels = Pixels(image);
  if (!pixels || pixels->GetNumberOfTuples() == 0)
  {
    return 0.0;
  }
  const int components = pixels->GetNumberOfComponents();
  const vtkIdType count = pixels->GetNumberOfTuples();
  const unsigned char* p = pixels->GetPointer(0);
  vtkIdType covered = 0;
  for (vtkIdType i = 0; i < count; ++i, p += components)
  {
    covered += IsBackground(p, components, background) ? 0 : 1;
  }
  return double(covered) / double(count);
}

vtkSmartPointer<vtkImageData> MakeDifferenceImage(
  vtkImageData* actual, vtkImageData* expected, int badPixelLevel)
{
  vtkUnsignedCharArray* a = Pixels(actual);
  vtkUnsignedCharArray* b = Pixels(expected);
  int da[3];
  int db[3];
  if (!a || !b)
  {
    return nullptr;
  }
  actual->GetDimensions(da);
  expected->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1])
  {
    return nullptr;
  }
  const int ca = a->GetNumberOfComponents();
  const int cb = b->GetNumberOfComponents();
  const int channels = (ca < 3 || cb < 3) ? 1 : 3;
  const vtkIdType count = vtkIdType(da[0]) * da[1];
  vtkNew<vtkUnsignedCharArray> out;
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(count);
  const unsigned char* pa = a->GetPointer(0);
  const unsigned char* pb = b->GetPointer(0);
  unsigned char* po = out->GetPointer(0);
  for (vtkIdType i = 0; i < count; ++i, pa += ca, pb += cb, po += 3)
  {
    int pixelMax = 0;
    for (int c = 0; c < 3; ++c)
    {
      const int cc = std::min(c, channels - 1);
      const int d = std::abs(int(pa[cc]) - int(pb[cc]));
      pixelMax = std::max(pixelMax, d);
      po[c] = static_cast<unsigned char>(std::min(255, 4 * d));
    }
    if (pixelMax > badPixelLevel)
    {
      po[0] = 255;
      po[1] = 0;
      po[2] = 0;
    }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(da[0], da[1], 1);
  image->GetPointData()->SetScalars(out);
  return image;
}

vtkSmartPointer<vtkImageData> ReadPng(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    return nullptr;
  }
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    return nullptr;
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reader->GetOutput());
  return Pixels(image) ? image : nullptr;
}

bool WritePng(vtkImageData* image, const std::string& path)
{
  if (!Pixels(image))
  {
    return false;
  }
  std::error_code ec;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty())
  {
    std::filesystem::create_directories(parent, ec);
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->Write();
  return writer->GetErrorCode() == 0 && std::filesystem::is_regular_file(path, ec);
}

bool ImagesIdentical(vtkImageData* a, vtkImageData* b, std::string* why)
{
  auto fail = [why](const std::string& text)
  {
    if (why)
    {
      *why = text;
    }
    return false;
  };
  vtkUnsignedCharArray* pa = Pixels(a);
  vtkUnsignedCharArray* pb = Pixels(b);
  if (!pa || !pb)
  {
    return fail("an image is missing or not unsigned char");
  }
  int da[3];
  int db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1] || da[2] != db[2] ||
    pa->GetNumberOfComponents() != pb->GetNumberOfComponents() ||
    pa->GetNumberOfTuples() != pb->GetNumberOfTuples())
  {
    return fail("dimensions or components differ");
  }
  const vtkIdType bytes = pa->GetNumberOfValues();
  const unsigned char* x = pa->GetPointer(0);
  const unsigned char* y = pb->GetPointer(0);
  vtkIdType differing = 0;
  vtkIdType first = -1;
  for (vtkIdType i = 0; i < bytes; ++i)
  {
    if (x[i] != y[i])
    {
      first = first < 0 ? i : first;
      ++differing;
    }
  }
  if (differing)
  {
    return fail(std::to_string(differing) + " of " + std::to_string(bytes) +
      " bytes differ (first at byte " + std::to_string(first) + ")");
  }
  return true;
}

} // namespace headless
} // namespace scenevis
