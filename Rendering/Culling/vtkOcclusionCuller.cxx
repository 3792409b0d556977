#include "vtkOcclusionCuller.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkOcclusionCuller);

vtkOcclusionCuller::vtkOcclusionCuller()
{
  this->OcclusionCulling = true;
}

vtkOcclusionCuller::~vtkOcclusionCuller() = default;

void vtkOcclusionCuller::SetOcclusionCulling(bool on)
{
  if (this->OcclusionCulling != on)
  {
    this->OcclusionCulling = on;
    this->Modified();
  }
}

void vtkOcclusionCuller::SetOcclusionRecordFile(const char* fileName)
{
  const std::string name = fileName ? fileName : "";
  if (this->OcclusionRecordFile != name)
  {
    this->OcclusionRecordFile = name;
    this->Modified();
  }
}

void vtkOcclusionCuller::SetOccluderCacheBudget(vtkIdType bytes)
{
  const std::size_t value = bytes > 0 ? static_cast<std::size_t>(bytes) : 0;
  if (this->OccluderCacheBudget != value)
  {
    this->OccluderCacheBudget = value;
    this->Modified();
  }
}

vtkIdType vtkOcclusionCuller::GetOccluderCacheBudget() const
{
  return static_cast<vtkIdType>(this->OccluderCacheBudget);
}

void vtkOcclusionCuller::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OcclusionCulling: " << this->OcclusionCulling << "\n";
  os << indent << "OccluderCacheBudget: " << this->OccluderCacheBudget << " bytes\n";
  os << indent << "OcclusionRecordFile: "
     << (this->OcclusionRecordFile.empty() ? "(none)" : this->OcclusionRecordFile) << "\n";
  os << indent << "NumberOfPropsCulledByOcclusion: " << this->NumberOfPropsCulledByOcclusion
     << "\n";
  os << indent << "NumberOfOcclusionTests: " << this->NumberOfOcclusionTests << "\n";
  os << indent << "OccluderMinimumPixelsPerTriangle: " << this->OccluderMinimumPixelsPerTriangle
     << "\n";
  os << indent << "NumberOfOccludersDrawn: " << this->NumberOfOccludersDrawn << "\n";
  os << indent << "NumberOfOccludersSkipped: " << this->NumberOfOccludersSkipped << "\n";
  os << indent << "NumberOfOccluderTriangles: " << this->NumberOfOccluderTriangles << "\n";
  os << indent << "OccluderRasterTime: " << this->OccluderRasterTime << " ms\n";
  os << indent << "CullTime: " << this->CullTime << " ms\n";
  os << indent << "DepthBufferBytes: " << this->DepthBufferBytes << "\n";
  os << indent << "OccluderCacheBytes: " << this->OccluderCacheBytes << "\n";
}
