/**
 * @file IdBuffer.h
 * @brief The ID-buffer oracles for tests: SceneVis::RenderingIdBuffer's (vtkSceneVisIdBuffer.h,
 *        what users link) in scenevis::testing.
 */
#ifndef scenevis_testing_IdBuffer_h
#define scenevis_testing_IdBuffer_h

#include <vtkSceneVisIdBuffer.h>

namespace scenevis
{
namespace testing
{

using idbuffer::ComputeEdgeMask;
using idbuffer::CullingCheck;
using idbuffer::CullingIsConservative;
using idbuffer::IdImage;
using idbuffer::IdImageToColor;
using idbuffer::IdRenderOptions;
using idbuffer::kMaxEncodableId;
using idbuffer::kNoId;
using idbuffer::OrderComparison;
using idbuffer::OrderMatchesDepth;
using idbuffer::RenderIdBuffer;
using idbuffer::RenderPainterIds;
using idbuffer::RenderVisibleIds;
using idbuffer::ReorderCells;
using idbuffer::VisibleSet;

} // namespace testing
} // namespace scenevis

#endif
