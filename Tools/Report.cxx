// What the commands write: JSON pieces, output file names, polydata and report files.
#include "Report.h"

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace scenevis
{
namespace tool
{

std::string JsonString(const std::string& text)
{
  std::string out = "\"";
  for (char c : text)
  {
    if (c == '"' || c == '\\')
    {
      out += '\\';
    }
    out += c;
  }
  return out + "\"";
}

std::string JsonVector(const double* v)
{
  std::ostringstream out;
  out << std::setprecision(9) << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  return out.str();
}

std::string JsonCamera(vtkCamera* camera, bool fixedClippingRange)
{
  std::ostringstream out;
  out << std::setprecision(9) << "{\"position\": " << JsonVector(camera->GetPosition())
      << ", \"focal_point\": " << JsonVector(camera->GetFocalPoint())
      << ", \"view_up\": " << JsonVector(camera->GetViewUp())
      << ", \"parallel\": " << (camera->GetParallelProjection() ? "true" : "false")
      << ", \"view_angle\": " << camera->GetViewAngle()
      << ", \"parallel_scale\": " << camera->GetParallelScale() << ", \"clipping_range\": ["
      << camera->GetClippingRange()[0] << ", " << camera->GetClippingRange()[1]
      << "], \"clipping_range_fixed\": " << (fixedClippingRange ? "true" : "false") << "}";
  return out.str();
}

std::string CameraFileName(const std::string& out, std::size_t index, const char* extension)
{
  const auto slash = out.find_last_of('/');
  auto dot = out.find_last_of('.');
  if (dot != std::string::npos && slash != std::string::npos && dot < slash)
    dot = std::string::npos; // a dot in a directory name
  return out.substr(0, dot) + "-" + std::to_string(index) +
    (dot == std::string::npos ? std::string(extension) : out.substr(dot));
}

std::string FrameFileName(const std::string& out, int frame, int frames)
{
  if (frames == 1)
  {
    return out;
  }
  const auto dot = out.find_last_of('.');
  std::ostringstream name;
  name << out.substr(0, dot) << "-" << std::setw(4) << std::setfill('0') << frame
       << (dot == std::string::npos ? ".png" : out.substr(dot));
  return name.str();
}

void WritePolyData(vtkPolyData* pd, const std::string& path)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(pd);
  writer->SetFileName(path.c_str());
  writer->SetDataModeToBinary();
  if (writer->Write() != 1)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

std::string JsonIds(const std::set<long long>& ids)
{
  std::ostringstream out;
  out << "[";
  bool first = true;
  for (const long long id : ids)
  {
    out << (first ? "" : ", ") << id;
    first = false;
  }
  return out.str() + "]";
}

void WriteReport(const std::string& text, const std::string& path)
{
  std::ofstream report(path);
  report << text;
  if (!report)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

} // namespace tool
} // namespace scenevis
