// Splitting one flattened polydata into parts by integer cell arrays (PartId, RoomId, ...).
#ifndef scenevis_tool_SplitParts_h
#define scenevis_tool_SplitParts_h

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkPolyData;

namespace scenevis
{
namespace tool
{

/**
 * The polygons of @p pd split into one polydata per distinct combination of values of the cell
 * arrays @p keys that it has (e.g. PartId, or RoomId then PartId), in ascending key order. Each
 * part gets its own compact points (in the order its cells first use them) with their point data,
 * and its cells' cell data, every array allocated at its final size.
 *
 * Linear in the size of the mesh: one pass over the cells assigns each to its part (a hash of the
 * key, skipped while consecutive cells share it), a counting sort lists each part's cells, and one
 * pass per part over its own cells maps points through a stamp array (no per-part scan of the whole
 * mesh, no per-part hash map). Extra memory while it runs: 8 bytes per cell and per point.
 *
 * Returns { pd } itself when it has none of the arrays, no cells, cells other than polygons, or a
 * single part. Values are read as integers (the callers check the arrays' types).
 */
std::vector<vtkSmartPointer<vtkPolyData>> SplitByKeys(
  vtkPolyData* pd, const std::vector<std::string>& keys);

} // namespace tool
} // namespace scenevis

#endif
