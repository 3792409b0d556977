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
 * and its cells' cell data, every array allocated at its final size. A part's cells are stored
 * with 32-bit offsets and ids whenever they fit (vtkCellArray's 32-bit storage: 16 instead of 32
 * bytes per triangle), so that the parts of a big model take less than the model they come from.
 *
 * Linear in the size of the mesh: one pass over the cells assigns each to its part (a hash of the
 * key, skipped while consecutive cells share it), a counting sort lists each part's cells, and one
 * pass per part over its own cells maps points through a stamp array (no per-part scan of the whole
 * mesh, no per-part hash map); a second pass copies each part's points and data. Extra memory
 * while it runs: 4 bytes per cell, 8 per point, and 8 per point of each part (its input points).
 *
 * Returns { pd } itself when it has none of the arrays, no cells, cells other than polygons, a
 * single part, or 2^32 - 1 cells or points or more (beyond any machine's memory today). Values
 * are read as integers (the callers check the arrays' types).
 *
 * With @p releaseInputPolygons, a caller that needs only the parts lets @p pd's polygons go as
 * soon as every part has its own (pd keeps its points and data, no cells): the input and its
 * parts then never fill memory together (peak below 2x the input on the 12.1M-triangle engine
 * grid). Polygons shared with another holder are only dereferenced.
 */
std::vector<vtkSmartPointer<vtkPolyData>> SplitByKeys(
  vtkPolyData* pd, const std::vector<std::string>& keys, bool releaseInputPolygons = false);

} // namespace tool
} // namespace scenevis

#endif
