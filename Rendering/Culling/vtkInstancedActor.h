/**
 * @class   vtkInstancedActor
 * @brief   One actor that draws its mapper's mesh at many placements (model matrices), each
 *          culled on its own by vtkOctreeCuller / vtkOcclusionCuller.
 *
 * A scene that places a few distinct meshes many times (glTF nodes sharing a mesh, VRML
 * DEF/USE, repeated CAD parts) drawn as one vtkActor per placement costs a vtkActor, its
 * transform objects and the culler's bookkeeping per placement (4.6 kB each measured in VTK 9.1,
 * 210 MB for 46,000 placements), for meshes that fit in a few MB. A vtkInstancedActor holds
 * the placements of one mesh as plain matrices (136 bytes each) and draws them with one mapper:
 *
 * @code
 * vtkNew<vtkInstancedActor> wheels;
 * wheels->SetMapper(wheelMapper);           // any vtkOpenGLPolyDataMapper
 * for (const auto& m : wheelMatrices)       // 16 doubles, row-major as vtkMatrix4x4
 *   wheels->AddPlacement(m.data());
 * renderer->AddActor(wheels);
 * vtkNew<vtkOcclusionCuller> culler;        // or vtkOctreeCuller
 * renderer->GetCullers()->RemoveAllItems();
 * renderer->AddCuller(culler);
 * @endcode
 *
 * Placement i is drawn with the model-to-world matrix GetMatrix() x PlacementMatrix(i) (the
 * actor's own position, orientation, scale and user matrix, identity by default, applied after
 * the placement's). Each placement is drawn exactly as a vtkActor with that matrix as its user
 * matrix would be (same shader, same MCDC and normal matrices, the same pixels): one draw call
 * per drawn placement with the mapper's buffers, uploaded once.
 *
 * Culling: vtkOctreeCuller and vtkOcclusionCuller know this class. They put every placement
 * in their hierarchy as if it were a prop of its own (its box: the mesh's box corners through
 * its matrix), cull placements by frustum, distance, size and occlusion (a visible placement
 * occludes with its own matrix), keep the actor while any placement survives, and tell it
 * which placements to draw (SetVisiblePlacements). Normal-cone culling does not apply to
 * placements. Other cullers (vtkFrustumCoverageCuller) see one prop, bounded by all its
 * placements, and leave the visible set alone: a visible set is kept until it is set again, so
 * after removing a placement-aware culler call SetAllPlacementsVisible().
 *
 * Bad input: AddPlacement refuses (error, returns -1) a matrix with a NaN or infinite element
 * or a singular one (its normals and bounds would not be finite); SetVisiblePlacements ignores
 * indices out of range (with an error).
 *
 * Not supported: translucent sorting across placements (vtkBSPTranslucentPass sorts actors;
 * use one vtkActor per placement for that), hardware picking of single placements, and
 * GetMatrix() as the placement's matrix (it is the actor's own).
 *
 * @sa vtkOctreeCuller vtkOcclusionCuller vtkGlyph3DMapper
 */
#ifndef vtkInstancedActor_h
#define vtkInstancedActor_h

#include "SceneVisRenderingCullingModule.h" // For export macro
#include "vtkOpenGLActor.h"

#include <vector> // For the placements

class SCENEVISRENDERINGCULLING_EXPORT vtkInstancedActor : public vtkOpenGLActor
{
public:
  static vtkInstancedActor* New();
  vtkTypeMacro(vtkInstancedActor, vtkOpenGLActor);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Appends a placement: @p matrix, 16 values row-major (vtkMatrix4x4's order), model to world
   * before the actor's own matrix; @p id, the caller's number for it (default: its index), what
   * GetPlacementId() returns. Returns the placement's index, or -1 (an error, nothing added)
   * for a non-finite or singular matrix. Calls Modified().
   */
  vtkIdType AddPlacement(const double matrix[16], vtkIdType id = -1);
  void RemoveAllPlacements();
  /// Room for @p count placements in all (AddPlacement then never reallocates below it).
  void ReservePlacements(vtkIdType count);
  vtkIdType GetNumberOfPlacements() const
  {
    return static_cast<vtkIdType>(this->PlacementIds.size());
  }
  /// The 16 values of placement @p i, or nullptr out of range.
  const double* GetPlacementMatrix(vtkIdType i) const VTK_SIZEHINT(16);
  /// The caller's number of placement @p i, or -1 out of range.
  vtkIdType GetPlacementId(vtkIdType i) const;
  ///@}

  /**
   * Model-to-world matrix of placement @p i as drawn (own matrix x placement), row-major.
   * Returns false out of range.
   */
  bool GetPlacementModelMatrix(vtkIdType i, double matrix[16]);

  /**
   * World bounds of placement @p i: the mapper's bounds' corners through its model-to-world
   * matrix (conservative). Returns false (bounds uninitialized) out of range or without a
   * mapper with data.
   */
  bool GetPlacementBounds(vtkIdType i, double bounds[6]);

  ///@{
  /**
   * Which placements are drawn: all by default; a placement-aware culler sets them every frame
   * it culls. Indices are placement indices (not ids), drawn in the order given. Does not call
   * Modified() (nothing moved). Indices out of range are dropped with an error.
   */
  void SetVisiblePlacements(const vtkIdType* indices, vtkIdType count) VTK_SIZEHINT(indices, count);
  void SetAllPlacementsVisible();
  bool GetAllPlacementsVisible() const { return this->AllVisible; }
  /// Placements drawn by the next render (all of them while GetAllPlacementsVisible()).
  vtkIdType GetNumberOfVisiblePlacements() const;
  /// Index of the k-th placement drawn, -1 out of range.
  vtkIdType GetVisiblePlacement(vtkIdType k) const;
  ///@}

  /// Union of the placements' bounds (GetPlacementBounds), uninitialized without placements.
  double* GetBounds() override;
  using Superclass::GetBounds;

  /// Draws every visible placement with the mapper, one after the other.
  void Render(vtkRenderer* ren, vtkMapper* mapper) override;

  /// The matrices of the placement being drawn (Render), else of the actor itself.
  void GetKeyMatrices(vtkMatrix4x4*& mcwc, vtkMatrix3x3*& normalMatrix) override;

  /// Bytes held for the placements and the visible set.
  std::size_t GetPlacementMemorySize() const;

protected:
  vtkInstancedActor();
  ~vtkInstancedActor() override;

private:
  vtkInstancedActor(const vtkInstancedActor&) = delete;
  void operator=(const vtkInstancedActor&) = delete;

  void SetKeyMatricesForPlacement(vtkIdType i);

  std::vector<double> Matrices; // 16 per placement
  std::vector<vtkIdType> PlacementIds;
  std::vector<vtkIdType> Visible;
  bool AllVisible = true;
  vtkIdType Current = -1; // the placement being drawn
  double PlacementUnion[6];
  vtkMTimeType UnionTime = 0;
};

#endif
