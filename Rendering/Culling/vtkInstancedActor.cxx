#include "vtkInstancedActor.h"

#include "vtkDataObject.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkInstancedActor);

namespace
{
bool IsIdentityMatrix(const double m[16])
{
  for (int i = 0; i < 16; ++i)
  {
    if (m[i] != (i % 5 == 0 ? 1.0 : 0.0))
    {
      return false;
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
vtkInstancedActor::vtkInstancedActor()
{
  vtkMath::UninitializeBounds(this->PlacementUnion);
}

//------------------------------------------------------------------------------
vtkInstancedActor::~vtkInstancedActor() = default;

//------------------------------------------------------------------------------
vtkIdType vtkInstancedActor::AddPlacement(const double matrix[16], vtkIdType id)
{
  if (!matrix || !std::all_of(matrix, matrix + 16, [](double v) { return std::isfinite(v); }))
  {
    vtkErrorMacro("AddPlacement: a matrix with a NaN or infinite element (not added).");
    return -1;
  }
  const double determinant = vtkMatrix4x4::Determinant(matrix);
  if (!std::isfinite(determinant) || !(std::abs(determinant) > 0.0))
  {
    vtkErrorMacro("AddPlacement: a singular matrix or one whose scale overflows (not added).");
    return -1;
  }
  const auto index = static_cast<vtkIdType>(this->PlacementIds.size());
  this->Matrices.insert(this->Matrices.end(), matrix, matrix + 16);
  this->PlacementIds.push_back(id < 0 ? index : id);
  // Placements move what the mapper draws: it must always ask for the key matrices.
  this->IsIdentity = 0;
  this->Modified();
  return index;
}

//------------------------------------------------------------------------------
void vtkInstancedActor::RemoveAllPlacements()
{
  this->Matrices.clear();
  this->PlacementIds.clear();
  this->Visible.clear();
  this->AllVisible = true;
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkInstancedActor::ReservePlacements(vtkIdType count)
{
  if (count > 0)
  {
    this->Matrices.reserve(16 * static_cast<std::size_t>(count));
    this->PlacementIds.reserve(static_cast<std::size_t>(count));
  }
}

//------------------------------------------------------------------------------
const double* vtkInstancedActor::GetPlacementMatrix(vtkIdType i) const
{
  if (i < 0 || i >= this->GetNumberOfPlacements())
  {
    return nullptr;
  }
  return this->Matrices.data() + 16 * i;
}

//------------------------------------------------------------------------------
vtkIdType vtkInstancedActor::GetPlacementId(vtkIdType i) const
{
  return i < 0 || i >= this->GetNumberOfPlacements() ? -1 : this->PlacementIds[i];
}

//------------------------------------------------------------------------------
bool vtkInstancedActor::GetPlacementModelMatrix(vtkIdType i, double matrix[16])
{
  const double* placement = this->GetPlacementMatrix(i);
  if (!placement)
  {
    return false;
  }
  const double* own = this->GetMatrix()->GetData();
  if (IsIdentityMatrix(own))
  {
    std::copy(placement, placement + 16, matrix); // exactly what a user matrix alone gives
  }
  else
  {
    vtkMatrix4x4::Multiply4x4(own, placement, matrix);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkInstancedActor::GetPlacementBounds(vtkIdType i, double bounds[6])
{
  vtkMath::UninitializeBounds(bounds);
  double m[16];
  if (!this->Mapper || !this->GetPlacementModelMatrix(i, m))
  {
    return false;
  }
  const double* box = this->Mapper->GetBounds();
  if (!box || !vtkMath::AreBoundsInitialized(box))
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = VTK_DOUBLE_MAX;
    bounds[2 * a + 1] = -VTK_DOUBLE_MAX;
  }
  for (int k = 0; k < 8; ++k)
  {
    const double p[3] = { box[k & 1], box[2 + ((k >> 1) & 1)], box[4 + ((k >> 2) & 1)] };
    double q[4];
    for (int r = 0; r < 4; ++r)
    {
      q[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    }
    for (int a = 0; a < 3; ++a)
    {
      const double v = q[a] / q[3];
      bounds[2 * a] = std::min(bounds[2 * a], v);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], v);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkInstancedActor::SetVisiblePlacements(const vtkIdType* indices, vtkIdType count)
{
  this->AllVisible = false;
  this->Visible.clear();
  const vtkIdType n = this->GetNumberOfPlacements();
  bool dropped = false;
  for (vtkIdType k = 0; indices && k < count; ++k)
  {
    if (indices[k] >= 0 && indices[k] < n)
    {
      this->Visible.push_back(indices[k]);
    }
    else
    {
      dropped = true;
    }
  }
  if (dropped)
  {
    vtkErrorMacro("SetVisiblePlacements: indices out of [0, " << n << ") dropped.");
  }
}

//------------------------------------------------------------------------------
void vtkInstancedActor::SetAllPlacementsVisible()
{
  this->AllVisible = true;
  this->Visible.clear();
}

//------------------------------------------------------------------------------
vtkIdType vtkInstancedActor::GetNumberOfVisiblePlacements() const
{
  return this->AllVisible ? this->GetNumberOfPlacements()
                          : static_cast<vtkIdType>(this->Visible.size());
}

//------------------------------------------------------------------------------
vtkIdType vtkInstancedActor::GetVisiblePlacement(vtkIdType k) const
{
  if (k < 0 || k >= this->GetNumberOfVisiblePlacements())
  {
    return -1;
  }
  return this->AllVisible ? k : this->Visible[k];
}

//------------------------------------------------------------------------------
double* vtkInstancedActor::GetBounds()
{
  vtkMTimeType time = this->GetMTime(); // with the user matrix or transform
  if (this->Mapper)
  {
    this->Mapper->GetBounds(); // brings the input up to date
    time = std::max(time, this->Mapper->GetMTime());
    if (vtkDataObject* data = this->Mapper->GetInputDataObject(0, 0))
    {
      time = std::max(time, data->GetMTime());
    }
  }
  if (time != this->UnionTime)
  {
    this->UnionTime = time;
    vtkMath::UninitializeBounds(this->PlacementUnion);
    bool any = false;
    for (vtkIdType i = 0; i < this->GetNumberOfPlacements(); ++i)
    {
      double b[6];
      if (!this->GetPlacementBounds(i, b))
      {
        continue;
      }
      for (int a = 0; a < 3; ++a)
      {
        this->PlacementUnion[2 * a] =
          any ? std::min(this->PlacementUnion[2 * a], b[2 * a]) : b[2 * a];
        this->PlacementUnion[2 * a + 1] =
          any ? std::max(this->PlacementUnion[2 * a + 1], b[2 * a + 1]) : b[2 * a + 1];
      }
      any = true;
    }
  }
  std::copy(this->PlacementUnion, this->PlacementUnion + 6, this->Bounds);
  return this->Bounds;
}

//------------------------------------------------------------------------------
void vtkInstancedActor::Render(vtkRenderer* ren, vtkMapper* mapper)
{
  const vtkIdType n = this->GetNumberOfVisiblePlacements();
  for (vtkIdType k = 0; k < n; ++k)
  {
    this->Current = this->GetVisiblePlacement(k);
    this->Superclass::Render(ren, mapper);
  }
  this->Current = -1;
}

//------------------------------------------------------------------------------
void vtkInstancedActor::GetKeyMatrices(vtkMatrix4x4*& mcwc, vtkMatrix3x3*& normalMatrix)
{
  // The same arithmetic as vtkOpenGLActor::GetKeyMatrices for a vtkActor whose matrix is the
  // placement's model matrix (so the same pixels), recomputed per placement.
  double m[16];
  if (this->Current < 0 || !this->GetPlacementModelMatrix(this->Current, m))
  {
    vtkMatrix4x4::DeepCopy(m, this->GetMatrix());
  }
  this->MCWCMatrix->DeepCopy(m);
  this->MCWCMatrix->Transpose();
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      this->NormalMatrix->SetElement(i, j, m[4 * i + j]);
    }
  }
  this->NormalMatrix->Invert();
  mcwc = this->MCWCMatrix;
  normalMatrix = this->NormalMatrix;
}

//------------------------------------------------------------------------------
std::size_t vtkInstancedActor::GetPlacementMemorySize() const
{
  return this->Matrices.capacity() * sizeof(double) +
    this->PlacementIds.capacity() * sizeof(vtkIdType) +
    this->Visible.capacity() * sizeof(vtkIdType);
}

//------------------------------------------------------------------------------
void vtkInstancedActor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfPlacements: " << this->GetNumberOfPlacements() << "\n";
  os << indent << "AllPlacementsVisible: " << (this->AllVisible ? "true" : "false") << "\n";
  os << indent << "NumberOfVisiblePlacements: " << this->GetNumberOfVisiblePlacements() << "\n";
  os << indent << "PlacementMemorySize: " << this->GetPlacementMemorySize() << "\n";
}
