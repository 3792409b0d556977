/**
 * @file KiCadBoard.h
 * @brief A real CAD assembly for culling tests and benchmarks: KiCad parts tiled onto boards.
 *
 * The KiCad 3D library (data cache key `kicad-wrl-dir`, Debian kicad-packages3d) holds 6,227
 * electronic parts as VRML. MakeKiCadBoard() picks a seeded selection of part files from a fixed
 * list of libraries (ICs, connectors, capacitors, resistors, LEDs, inductors, crystals, power
 * modules), reads each file ONCE through LoadModel() (which inlines `material USE` so parts keep
 * their KiCad colours), and places instances of them on a grid of boards (translated, optionally
 * turned by 90 degrees about z, each board a thin green plate) until a target triangle count is
 * reached. The result comes in the two forms a CAD viewer meets:
 *  - many actors: one KiCadInstance per placed part; instances of a part SHARE its polydata
 *    (nothing is copied per instance), the placement is a matrix for vtkProp3D::SetUserMatrix();
 *  - one mesh: every instance transformed and merged into one polydata (optional, it is big) with
 *    cell arrays "PartId" (vtkIdTypeArray, the instance index) and "Colors" (RGBA unsigned char
 *    cell scalars, the part's KiCad material colours).
 * The same options and seed give the same board (file order is sorted, the generator is
 * std::mt19937 with fixed distributions implemented here, not the library's).
 * Units are those of the KiCad files (1 unit = 2.54 mm).
 */
#ifndef scenevis_testing_KiCadBoard_h
#define scenevis_testing_KiCadBoard_h

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <cstddef>
#include <string>
#include <vector>

class vtkMatrix4x4;
class vtkPolyData;

namespace scenevis
{
namespace testing
{

/// Options of MakeKiCadBoard().
struct KiCadBoardOptions
{
  /// Folder holding <Library>.3dshapes/*.wrl; empty: DataFile("kicad-wrl-dir").
  std::string directory;
  /// Distinct part files read (each once), spread over the fixed library list.
  std::size_t partTypes = 48;
  /// Stop placing when the instances reach this many triangles...
  std::size_t targetTriangles = 10000000;
  /// ...or this many parts (0 = no limit), whichever comes first.
  std::size_t maximumParts = 0;
  /// Part files with more triangles than this are not selected (keeps one part from dominating).
  std::size_t maximumTrianglesPerPart = 60000;
  unsigned seed = 1;
  /// Turn every other instance (chosen at random) by 90 degrees about z.
  bool rotate = true;
  /// Build the merged one-mesh form as well (KiCadBoard::merged).
  bool merged = true;
};

/// One placed part (or board plate): shared geometry, placement, and a representative colour.
struct KiCadInstance
{
  vtkSmartPointer<vtkPolyData> polys;   ///< shared by all instances of the part; "Colors" scalars
  vtkSmartPointer<vtkMatrix4x4> matrix; ///< part coordinates -> board coordinates
  double color[3] = { 1, 1, 1 };        ///< the part's most frequent (by cells) material colour
  double opacity = 1.0;                 ///< the smallest material opacity of the part
  std::size_t partType = 0;             ///< index into KiCadBoard::partFiles; plates: npos
  vtkIdType triangles = 0;
};

/// Result of MakeKiCadBoard().
struct KiCadBoard
{
  std::vector<KiCadInstance> instances;
  vtkSmartPointer<vtkPolyData> merged; ///< nullptr unless KiCadBoardOptions::merged
  std::vector<std::string> partFiles;  ///< files read, relative to the directory
  std::size_t boards = 0;
  /// Over all instances; with `merged`, its triangle count (which drops the rare triangles that
  /// collapse when points are rounded to float).
  vtkIdType triangles = 0;
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  /// Set when nothing could be built (data absent, no readable part): callers skip.
  std::string error;

  bool Empty() const { return this->instances.empty(); }
};

/**
 * Build a board assembly from KiCad parts (see the file comment). Never throws; on missing data
 * returns an empty board with @c error set ("data absent: ..."), so tests can skip.
 */
KiCadBoard MakeKiCadBoard(const KiCadBoardOptions& options = KiCadBoardOptions());

} // namespace testing
} // namespace scenevis

#endif
