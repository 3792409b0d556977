/**
 * @file vtkBSPFragmentSet.h
 * @brief (private header) The convex fragments of one polydata, as vtkBSPSortedPolyDataMapper draws
 * them, in a form that does not depend on who built the BSP tree.
 *
 * Point ids below the input's point count are the input's own points; split point i is point
 * `numberOfInputPoints + i`, at lerp(point(a), point(b), t) with a, b smaller than its id (the
 * same convention as scenevis::bsp::Tree, see Core/include/scenevis/BspTree.h). Every per-point
 * attribute is interpolated the same way.
 *
 * vtkBSPSortedPolyDataMapper makes one from its own tree (standalone use); vtkBSPTranslucentPass
 * makes one per actor from the fragments of ONE world-space tree over all translucent actors.
 */
#ifndef vtkBSPFragmentSet_h
#define vtkBSPFragmentSet_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include "scenevis/BspBuilder.h" // For scenevis::bsp::BuildConfig
#include "scenevis/BspTree.h"    // For scenevis::bsp::SplitPoint

#include <cstdint>
#include <vector>

struct vtkBSPFragmentSet
{
  /// The polydata the point and cell ids refer to.
  vtkSmartPointer<vtkPolyData> Input;
  /// Split points, in creation order (point id = Input->GetNumberOfPoints() + index).
  std::vector<scenevis::bsp::SplitPoint> Splits;
  /// Fragment f uses Vertices[Offsets[f] .. Offsets[f+1]) (convex, >= 3 vertices).
  std::vector<std::uint32_t> Offsets{ 0 };
  std::vector<std::uint32_t> Vertices;
  /// Input cell id of every fragment (for cell data).
  std::vector<vtkIdType> Cells;

  std::size_t FragmentCount() const { return this->Offsets.size() - 1; }

  /// How the mapper and the pass build their trees: the default partition on every core (the
  /// tree is identical for any thread count).
  static scenevis::bsp::BuildConfig BuildConfig()
  {
    scenevis::bsp::BuildConfig config;
    config.threads = 0;
    return config;
  }
};

#endif
// VTK-HeaderTest-Exclude: vtkBSPFragmentSet.h
