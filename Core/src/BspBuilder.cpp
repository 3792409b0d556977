#include "scenevis/BspBuilder.h"

#include "BspLeafBuilder.h"
#include "PolygonPieces.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <memory>
#include <thread>
#include <utility>

namespace scenevis
{
namespace bsp
{
namespace
{

/// Free planes are tried only on lists longer than this. Below it the scored polygon planes
/// decide alone, which on a convex patch means a chain at most this deep: much cheaper than the
/// splits a free plane costs there (each plane through a patch of m triangles cuts about
/// sqrt(m) of them, so stopping free planes at m0 leaves about 5 / sqrt(m0) splits per input
/// triangle on a generic sphere: ~0.46 at 128, while the leaf chains stay at most 128 deep).
constexpr std::uint32_t kMinFreePlaneList = 128;

/// Above this many fragments a polygon plane that leaves every other fragment on one side (it
/// would peel off one polygon per level) is not taken while a free plane separates anything.
constexpr std::uint32_t kMaxChainList = 128;

/// Free-plane medians are taken over at most this many (strided) centroids: an approximate median
/// balances as well and keeps the cost per node independent of the list size.
constexpr std::uint32_t kMedianSample = 1024;

/// Per effort level (BuildConfig::Effort, measured trade-off in BspBuilder.h):
/// - sweepSample: free-plane sweeps (see chooseScored) sort the extents of at most this many
///   (strided) fragments per axis. 64 finds the gaps between parts as well as 256 (fragments
///   within 0.3 %) at a quarter of the gathering and less than a quarter of the sorting.
/// - extraCandidateList / candidateFactor: lists of at most extraCandidateList fragments are
///   scored against every polygon anyway, so they try candidateFactor * BuildConfig::candidates
///   polygon planes. Most of the gain of more candidates comes from the shortest lists.
/// - boundStride: the early-out bound of a candidate's score is checked every this many sample
///   fragments (checking it costs about as much as classifying a fragment).
struct EffortParameters
{
  std::uint32_t sweepSample;
  std::uint32_t extraCandidateList;
  std::uint32_t candidateFactor;
  std::uint32_t boundStride;
};

EffortParameters effortParameters(BuildConfig::Effort effort)
{
  return effort == BuildConfig::Effort::Thorough ? EffortParameters{ 256, 128, 2, 1 }
                                                 : EffortParameters{ 64, 32, 2, 4 };
}

/// Tolerance floor in units of the coordinate resolution: max|coordinate| * DBL_EPSILON is the
/// rounding step of the input coordinates (an input point, or a split point stored in world
/// coordinates, is off its exact position by up to half of it), and a plane fitted through
/// rounded points is off by a few steps more; 16 steps cover both with margin.
constexpr double kResolutionSteps = 16.0;

/// Estimated cost of building the subtree of a list of m fragments, m log2 m (a balanced tree
/// handles every fragment once per level); the SubtreeCost score sums it over both children.
double subtreeCost(double m)
{
  return m > 1.0 ? m * std::log2(m) : 0.0;
}

/// With BuildConfig::threads > 1, a node whose two sides both have at least this many fragments
/// hands its back side to a worker thread (one worker at a time; the front side stays here).
constexpr std::uint32_t kMinParallelList = 16384;

/// A list that would become an ordered leaf needing a fallback first tries at most this many of
/// its pairs' separating planes as a partition that splits nothing (each costs a pass over the
/// list).
constexpr std::uint32_t kSeparatingTries = 64;

std::uint64_t splitmix64(std::uint64_t& state)
{
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// Key of a child task: derived from the parent's key only, so the random choices of a subtree
/// do not depend on the order in which subtrees are processed.
std::uint64_t childKey(std::uint64_t key, bool front)
{
  std::uint64_t state = key ^ (front ? 0x5851f42d4c957f2dull : 0x14057b7ef767814full);
  return splitmix64(state);
}

struct Rng
{
  std::uint64_t state;
  /// Uniform in [0, n) (multiply-shift; no modulo bias worth caring about for sampling).
  std::uint32_t below(std::uint32_t n)
  {
    return static_cast<std::uint32_t>(((splitmix64(state) >> 32) * n) >> 32);
  }
};

using detail::Back;
using detail::BuildGeometry;
using detail::Frag;
using detail::Front;
using detail::On;
using detail::Side;
using detail::Straddle;

struct Task
{
  std::uint32_t begin;
  std::uint32_t end;
  std::uint32_t parent;
  std::uint32_t depth;
  std::uint64_t key;
  bool isFront;      // which child of `parent` this task becomes
  bool oneSidedRun;  // see Builder::run()
  bool noLeaf = false; // a leaf's fallback subtree: split as usual, no ordered leaves in it
};

/**
 * Map from an undirected edge (min id, max id) to the split point made on it, valid for one node.
 * Open addressing with generation stamps: clearing is O(1), which matters because it happens at
 * every node that splits anything.
 */
class EdgeCache
{
public:
  void clear()
  {
    ++Stamp;
    Used = 0;
    if (Stamp == 0)
    {
      for (Slot& s : Slots)
      {
        s.stamp = 0;
      }
      Stamp = 1;
    }
  }

  std::uint32_t find(std::uint64_t key) const
  {
    if (Slots.empty())
    {
      return kNone;
    }
    const std::size_t mask = Slots.size() - 1;
    for (std::size_t i = hash(key) & mask;; i = (i + 1) & mask)
    {
      const Slot& s = Slots[i];
      if (s.stamp != Stamp)
      {
        return kNone;
      }
      if (s.key == key)
      {
        return s.value;
      }
    }
  }

  void insert(std::uint64_t key, std::uint32_t value)
  {
    if ((Used + 1) * 2 > Slots.size())
    {
      grow();
    }
    place(key, value);
    ++Used;
  }

  std::size_t memoryBytes() const { return Slots.capacity() * sizeof(Slot); }

private:
  struct Slot
  {
    std::uint64_t key;
    std::uint32_t value;
    std::uint32_t stamp;
  };

  static std::size_t hash(std::uint64_t key)
  {
    return static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ull) >> 20);
  }

  void place(std::uint64_t key, std::uint32_t value)
  {
    const std::size_t mask = Slots.size() - 1;
    std::size_t i = hash(key) & mask;
    while (Slots[i].stamp == Stamp)
    {
      i = (i + 1) & mask;
    }
    Slots[i] = Slot{ key, value, Stamp };
  }

  void grow()
  {
    std::vector<Slot> old;
    old.swap(Slots);
    Slots.assign(std::max<std::size_t>(64, old.size() * 2), Slot{ 0, 0, 0 });
    const std::uint32_t stamp = Stamp;
    Stamp = 1;
    for (const Slot& s : old)
    {
      if (s.stamp == stamp)
      {
        place(s.key, s.value);
      }
    }
  }

  std::vector<Slot> Slots;
  std::uint32_t Stamp = 1;
  std::size_t Used = 0;
};

class Builder
{
public:
  Builder(const PolygonMesh& mesh, const BuildConfig& config, const ProgressCallback& progress)
    : Mesh(mesh)
    , Config(config)
    , Progress(progress)
    , Effort(effortParameters(config.effort))
  {
  }

  Tree run();

private:
  /// Processes one task (one node): picks its plane, splits its list, pushes its children.
  void step(const Task& task, std::vector<Task>& tasks);
  enum class LeafResult
  {
    Made,    ///< The list is an ordered leaf now.
    Split,   ///< Some pair intersects: nothing was changed, split the list as usual.
    Separate ///< `separating` splits none of the list: partition by it (nothing was changed).
  };
  /// Makes `task`'s list an ordered leaf (BspTree.h) when every pair is coplanar or separable,
  /// and pushes the fallback subtree's task when the leaf needs one, unless the leaf would need
  /// one and a gap plane (gapPlane) or one of its pairs' separating planes (up to
  /// kSeparatingTries of them) splits none of the list.
  LeafResult makeLeaf(const Task& task, std::vector<Task>& tasks, glm::dvec4& separating);
  /// The first piece in `task`'s list whose plane splits none of the list's fragments (kNone
  /// when every one splits some).
  std::uint32_t splitFreePiece(const Task& task) const;
  /// An axis-aligned plane through the most balanced gap between the extents of `list`'s
  /// fragments (fragments on both sides, none split); false when no axis has a gap.
  bool gapPlane(const Frag* list, std::uint32_t n, glm::dvec4& plane);
  /// Points `task`'s parent (a node, a leaf's fallback, or the root) at `reference`.
  void link(const Task& task, std::uint32_t reference);
  /// Builds the subtree of `task` (a list in this builder's Arena) in a worker builder.
  void fork(const Task& task);
  /// Waits for the worker and appends its subtree as if it had been built here, in order.
  void join();
  bool parallel() const { return Threads > 1; }
  double signedDistance(const glm::dvec4& plane, std::uint32_t id) const
  {
    const glm::dvec3& p = Local[id];
    return plane.x * p.x + plane.y * p.y + plane.z * p.z + plane.w;
  }

  /// The current points, vertices and planes (valid until the next split adds to them).
  BuildGeometry geometry() const
  {
    return BuildGeometry{ Local.data(), Verts.data(), Planes, Tol };
  }

  Side classify(const glm::dvec4& plane, const Frag& f) const
  {
    return geometry().classify(plane, f);
  }


  struct Choice
  {
    glm::dvec4 plane{ 0.0 };
    std::uint32_t piece = kNone; // kNone: free plane
    glm::dvec4 fallbackPlane{ 0.0 };
    std::uint32_t fallbackPiece = kNone;
  };
  Choice chooseScored(const Task& task, std::uint32_t n);
  std::uint32_t splitPoint(const glm::dvec4& plane, std::uint32_t a, std::uint32_t b);
  void split(const Frag& f, const glm::dvec4& plane, Frag& front, Frag& back);

  const PolygonMesh& Mesh;
  const BuildConfig& Config;
  const ProgressCallback& Progress;
  const EffortParameters Effort;
  Tree Out;
  double Tol = 0.0;

  std::vector<glm::dvec3> Local;    // points relative to Out.origin: all classification uses these
  std::vector<glm::dvec4> PiecePlane;
  std::vector<std::uint32_t> PieceSource;
  const glm::dvec4* Planes = nullptr;      // PiecePlane, shared read-only with the worker
  const std::uint32_t* Sources = nullptr;  // PieceSource, likewise
  bool Scored = true;
  std::size_t Placed = 0;

  // Parallel build (see fork / join). A worker builds the back subtree of node ForkNode with
  // point ids numbered as if it started at ForkPoints; join() renumbers and appends it.
  unsigned Threads = 1;
  std::atomic<bool>* Cancel = nullptr;
  std::unique_ptr<Builder> Worker;
  std::thread WorkerThread;
  std::exception_ptr WorkerError;
  std::atomic<bool> CancelFlag{ false };
  std::uint32_t ForkNode = kNone;
  std::size_t ForkPoints = 0;
  std::size_t ForkStack = 0;
  std::vector<std::uint32_t> PieceCount; // vertices of each piece; pieces are consecutive in Verts
  std::vector<std::uint32_t> Verts; // vertex arena of all fragments (append-only)
  std::vector<Frag> Arena;          // fragment lists of pending tasks, used as a stack
  std::vector<Frag> FrontScratch;
  std::vector<Frag> OwnScratch;
  std::vector<std::uint8_t> Codes;
  std::vector<std::uint32_t> IdScratch;
  std::vector<std::uint32_t> BackScratch;
  std::vector<double> DistScratch;
  std::vector<glm::dvec3> CentroidScratch;
  std::vector<std::pair<double, std::uint32_t>> AxisScratch;
  std::vector<glm::dvec3> SweepBox;
  std::vector<double> SweepLo;
  std::vector<double> SweepHi;
  std::vector<double> SweepFlat;
  std::vector<double> SweepCost;
  std::vector<double> CostTable;
  detail::LeafBuilder Leaf;
  std::vector<std::pair<double, double>> GapScratch;
  std::size_t FallbackFragments = 0;
  std::vector<std::uint32_t> SamplePiece;
  std::vector<std::uint32_t> SampleEnd;
  std::vector<glm::dvec3> SamplePoints;
  EdgeCache Cache;

};

std::uint32_t Builder::splitPoint(const glm::dvec4& plane, std::uint32_t a, std::uint32_t b)
{
  const std::uint32_t lo = std::min(a, b);
  const std::uint32_t hi = std::max(a, b);
  const std::uint64_t key = (static_cast<std::uint64_t>(lo) << 32) | hi;
  const std::uint32_t cached = Cache.find(key);
  if (cached != kNone)
  {
    return cached;
  }
  // Always from the smaller id: both polygons sharing the edge would compute the same bits, and
  // the cache makes sure they also share the id.
  const double slo = signedDistance(plane, lo);
  const double shi = signedDistance(plane, hi);
  const double t = slo / (slo - shi);
  const glm::dvec3 localLo = Local[lo];
  const glm::dvec3 localHi = Local[hi];
  const glm::dvec3 worldLo = Out.points[lo];
  const glm::dvec3 worldHi = Out.points[hi];
  Local.push_back(localLo + (localHi - localLo) * t);
  Out.points.push_back(worldLo + (worldHi - worldLo) * t);
  Out.splitPoints.push_back(SplitPoint{ lo, hi, t });
  const auto id = static_cast<std::uint32_t>(Out.points.size() - 1);
  Cache.insert(key, id);
  return id;
}

void Builder::split(const Frag& f, const glm::dvec4& plane, Frag& front, Frag& back)
{
  const std::uint32_t m = f.count;
  IdScratch.assign(Verts.begin() + f.first, Verts.begin() + f.first + m);
  DistScratch.resize(m);
  for (std::uint32_t k = 0; k < m; ++k)
  {
    const double s = signedDistance(plane, IdScratch[k]);
    DistScratch[k] = s > Tol ? 1.0 : (s < -Tol ? -1.0 : 0.0);
  }
  BackScratch.clear();
  front.piece = back.piece = f.piece;
  front.first = static_cast<std::uint32_t>(Verts.size());
  for (std::uint32_t k = 0; k < m; ++k)
  {
    const std::uint32_t next = k + 1 == m ? 0 : k + 1;
    const double ck = DistScratch[k];
    const double cn = DistScratch[next];
    if (ck >= 0.0)
    {
      Verts.push_back(IdScratch[k]);
    }
    if (ck <= 0.0)
    {
      BackScratch.push_back(IdScratch[k]);
    }
    if (ck * cn < 0.0)
    {
      const std::uint32_t id = splitPoint(plane, IdScratch[k], IdScratch[next]);
      Verts.push_back(id);
      BackScratch.push_back(id);
    }
  }
  front.count = static_cast<std::uint32_t>(Verts.size()) - front.first;
  back.first = static_cast<std::uint32_t>(Verts.size());
  back.count = static_cast<std::uint32_t>(BackScratch.size());
  Verts.insert(Verts.end(), BackScratch.begin(), BackScratch.end());
}

Builder::Choice Builder::chooseScored(const Task& task, std::uint32_t n)
{
  Rng rng{ task.key };
  const Frag* list = Arena.data() + task.begin;
  const auto candidates = static_cast<std::uint32_t>(std::max(1, Config.candidates));
  const auto sampleSize =
    std::min(n, static_cast<std::uint32_t>(std::max(1, Config.samplePolygons)));
  constexpr double kInfinity = std::numeric_limits<double>::infinity();

  // The sample's vertices, gathered once: every candidate plane is scored against them, and
  // streaming through one small array beats chasing Verts -> Local for each of them.
  SamplePiece.resize(sampleSize);
  SampleEnd.resize(sampleSize);
  SamplePoints.clear();
  for (std::uint32_t j = 0; j < sampleSize; ++j)
  {
    const Frag& f = list[(static_cast<std::uint64_t>(j) * n) / sampleSize];
    SamplePiece[j] = f.piece;
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      SamplePoints.push_back(Local[Verts[f.first + k]]);
    }
    SampleEnd[j] = static_cast<std::uint32_t>(SamplePoints.size());
  }
  const glm::dvec3* samplePoints = SamplePoints.data();
  auto classifySample = [&](const glm::dvec4& plane, std::uint32_t j) -> Side
  {
    bool front = false;
    bool back = false;
    for (std::uint32_t k = j == 0 ? 0 : SampleEnd[j - 1]; k < SampleEnd[j]; ++k)
    {
      const glm::dvec3& p = samplePoints[k];
      const double sd = plane.x * p.x + plane.y * p.y + plane.z * p.z + plane.w;
      front |= sd > Tol;
      back |= sd < -Tol;
    }
    return static_cast<Side>((front ? Front : On) | (back ? Back : On));
  };

  // Returns +inf as soon as the score provably exceeds `cutoff` (ties are still scored exactly,
  // so the lower candidate index wins them), and for a free plane that separates nothing.
  // SubtreeCost: subtreeCost(front + splits) + subtreeCost(back + splits), counts scaled from the
  // sample to the list (a split fragment goes to both sides; coplanar fragments of a polygon
  // plane leave the list, so planes shared by many polygons are cheap). SplitsAndBalance:
  // splits * splitWeight + |front - back| on the sample.
  // SubtreeCost applies to lists up to kMinFreePlaneList: most splits happen there, and the depth
  // below is bounded by the list size anyway; above, its weak preference for balance would let
  // peeled chains deepen the tree (and the incremental traversal's work), so balance is kept.
  const bool subtree =
    Config.score == BuildConfig::Score::SubtreeCost && n <= kMinFreePlaneList;
  // Counts are whole numbers up to sampleSize: tabulate subtreeCost of their scaled values.
  CostTable.resize(sampleSize + 1);
  for (std::uint32_t k = 0; subtree && k <= sampleSize; ++k)
  {
    CostTable[k] = subtreeCost(static_cast<double>(k) * n / sampleSize);
  }
  const double* costTable = CostTable.data();
  auto finalScore = [&](double splits, double front, double back) -> double
  {
    return subtree ? costTable[static_cast<std::uint32_t>(front + splits)] +
        costTable[static_cast<std::uint32_t>(back + splits)]
                   : splits * Config.splitWeight + std::abs(front - back);
  };
  bool oneSided = false;
  auto score = [&](const glm::dvec4& plane, std::uint32_t piece, double cutoff) -> double
  {
    oneSided = false;
    double splits = 0;
    double front = 0;
    double back = 0;
    double remaining = sampleSize;
    for (std::uint32_t j = 0; j < sampleSize; ++j)
    {
      remaining -= 1;
      if (SamplePiece[j] == piece)
      {
        continue;
      }
      switch (classifySample(plane, j))
      {
        case Front:
          front += 1;
          break;
        case Back:
          back += 1;
          break;
        case Straddle:
          splits += 1;
          break;
        default:
          if (piece == kNone)
          {
            back += 1; // a free plane owns nothing: coplanar fragments go behind it
          }
          break;
      }
      // Checked every boundStride fragments only.
      if (Effort.boundStride > 1 && j % Effort.boundStride != Effort.boundStride - 1)
      {
        continue;
      }
      // Lower bounds of the final score. SubtreeCost: the remaining fragments are put where they
      // cost least, filling up the smaller side (C is convex); that they could also be coplanar
      // with a polygon plane is ignored, which makes this a (deterministic) pruning heuristic
      // rather than a bound for planes shared by many polygons.
      double bound;
      if (subtree)
      {
        const double a = front + splits;
        const double b = back + splits;
        const double lo = std::min(a, b) + remaining;
        const double hi = std::max(a, b);
        const double even = std::floor((a + b + remaining) * 0.5);
        bound = lo <= hi ? costTable[static_cast<std::uint32_t>(lo)] +
            costTable[static_cast<std::uint32_t>(hi)]
                         : costTable[static_cast<std::uint32_t>(even)] +
            costTable[static_cast<std::uint32_t>(a + b + remaining - even)];
      }
      else
      {
        bound = splits * Config.splitWeight + std::max(0.0, std::abs(front - back) - remaining);
      }
      if (bound > cutoff)
      {
        return kInfinity;
      }
    }
    if (splits == 0 && (front == 0 || back == 0))
    {
      if (piece == kNone)
      {
        return kInfinity;
      }
      oneSided = true;
    }
    return finalScore(splits, front, back);
  };

  // Free planes first: on big lists one usually wins, and its score then cuts the polygon
  // candidates' evaluation short.
  double bestFree = kInfinity;
  glm::dvec4 freePlane(0.0);
  if (Config.allowFreePlanes && n > kMinFreePlaneList)
  {
    const std::uint32_t medianSample = std::min(n, kMedianSample);
    CentroidScratch.resize(medianSample);
    for (std::uint32_t j = 0; j < medianSample; ++j)
    {
      const Frag& f =
        list[static_cast<std::uint32_t>((static_cast<std::uint64_t>(j) * n) / medianSample)];
      glm::dvec3 c(0.0);
      for (std::uint32_t k = 0; k < f.count; ++k)
      {
        c += Local[Verts[f.first + k]];
      }
      CentroidScratch[j] = c / static_cast<double>(f.count);
    }
    AxisScratch.resize(medianSample);
    for (int axis = 0; axis < 3; ++axis)
    {
      for (std::uint32_t j = 0; j < medianSample; ++j)
      {
        AxisScratch[j] = { CentroidScratch[j][axis], j };
      }
      const auto mid = AxisScratch.begin() + medianSample / 2;
      std::nth_element(AxisScratch.begin(), mid, AxisScratch.end());
      // Besides the plane through the median centroid, also try the one through the median
      // fragment's vertex nearest to it: on meshes with shared coordinates (latitude rings, CAD
      // grids) it passes through vertices instead of cutting the polygons around them.
      const double median = mid->first;
      const Frag& medianFrag = list[static_cast<std::uint32_t>(
        (static_cast<std::uint64_t>(mid->second) * n) / medianSample)];
      double snapped = Local[Verts[medianFrag.first]][axis];
      for (std::uint32_t k = 1; k < medianFrag.count; ++k)
      {
        const double c = Local[Verts[medianFrag.first + k]][axis];
        if (std::abs(c - median) < std::abs(snapped - median))
        {
          snapped = c;
        }
      }
      for (int variant = 0; variant < 2; ++variant)
      {
        if (variant == 1 && snapped == median)
        {
          continue;
        }
        glm::dvec4 plane(0.0);
        plane[axis] = 1.0;
        plane.w = -(variant == 0 ? median : snapped);
        const double sc = score(plane, kNone, bestFree);
        if (sc < bestFree)
        {
          bestFree = sc;
          freePlane = plane;
        }
      }
    }
    // Sweep: the axis plane through a fragment's extreme coordinate that scores best on the
    // fragments' extents. It finds gaps between the parts of an assembly and planes along
    // aligned faces, which a median never hits; the winner is then scored like the others.
    const std::uint32_t m = std::min(n, Effort.sweepSample);
    // Bounding boxes of the strided sample, gathered once for all three axes.
    SweepBox.resize(2 * static_cast<std::size_t>(m));
    for (std::uint32_t j = 0; j < m; ++j)
    {
      const Frag& f = list[static_cast<std::uint32_t>((static_cast<std::uint64_t>(j) * n) / m)];
      glm::dvec3 lo = Local[Verts[f.first]];
      glm::dvec3 hi = lo;
      for (std::uint32_t k = 1; k < f.count; ++k)
      {
        const glm::dvec3& c = Local[Verts[f.first + k]];
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
      }
      SweepBox[2 * j] = lo;
      SweepBox[2 * j + 1] = hi;
    }
    SweepCost.resize(m + 1);
    for (std::uint32_t k = 0; k <= m; ++k)
    {
      SweepCost[k] = subtree ? subtreeCost(static_cast<double>(k) * n / m)
                             : static_cast<double>(k) * sampleSize / m;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      SweepLo.resize(m);
      SweepHi.resize(m);
      SweepFlat.clear();
      for (std::uint32_t j = 0; j < m; ++j)
      {
        const double lo = SweepBox[2 * j][axis];
        const double hi = SweepBox[2 * j + 1][axis];
        SweepLo[j] = lo;
        SweepHi[j] = hi;
        if (hi - lo <= 2.0 * Tol)
        {
          SweepFlat.push_back(0.5 * (lo + hi)); // may lie on the plane (goes behind it)
        }
      }
      std::sort(SweepLo.begin(), SweepLo.end());
      std::sort(SweepHi.begin(), SweepHi.end());
      std::sort(SweepFlat.begin(), SweepFlat.end());
      // Positions in ascending order; every count below only moves forward.
      double best = kInfinity;
      double bestPosition = 0.0;
      const std::size_t flats = SweepFlat.size();
      std::size_t iLo = 0;
      std::size_t iHi = 0;
      std::size_t backOrOn = 0;
      std::size_t belowLo = 0;
      std::size_t flatBelow = 0;
      std::size_t flatUpTo = 0;
      while (iLo < m || iHi < m)
      {
        const bool takeLo = iHi >= m || (iLo < m && SweepLo[iLo] <= SweepHi[iHi]);
        const double v = takeLo ? SweepLo[iLo++] : SweepHi[iHi++];
        while (backOrOn < m && SweepHi[backOrOn] <= v + Tol)
        {
          ++backOrOn;
        }
        while (belowLo < m && SweepLo[belowLo] < v - Tol)
        {
          ++belowLo;
        }
        while (flatUpTo < flats && SweepFlat[flatUpTo] <= v + Tol)
        {
          ++flatUpTo;
        }
        while (flatBelow < flats && SweepFlat[flatBelow] < v - Tol)
        {
          ++flatBelow;
        }
        // Fragments both back-or-on and front-or-on lie on the plane: estimated from the flat
        // ones' mid-points, clamped so that every count stays within [0, m].
        const std::size_t frontOrOn = m - belowLo;
        const std::size_t on = std::clamp(flatUpTo - flatBelow,
          backOrOn + frontOrOn > m ? backOrOn + frontOrOn - m : std::size_t{ 0 },
          std::min(backOrOn, frontOrOn));
        const double back = static_cast<double>(backOrOn);
        const double front = static_cast<double>(frontOrOn - on);
        const double straddle = static_cast<double>(m) - back - front;
        if (straddle == 0 && (front == 0 || back == 0))
        {
          continue;
        }
        const auto iStraddle = static_cast<std::uint32_t>(straddle);
        const auto iFront = static_cast<std::uint32_t>(front);
        const auto iBack = static_cast<std::uint32_t>(back);
        const double sc = subtree
          ? SweepCost[iFront + iStraddle] + SweepCost[iBack + iStraddle]
          : SweepCost[iStraddle] * Config.splitWeight + std::abs(SweepCost[iFront] - SweepCost[iBack]);
        if (sc < best)
        {
          best = sc;
          bestPosition = v;
        }
      }
      if (best < kInfinity)
      {
        glm::dvec4 plane(0.0);
        plane[axis] = 1.0;
        plane.w = -bestPosition;
        const double sc = score(plane, kNone, bestFree);
        if (sc < bestFree)
        {
          bestFree = sc;
          freePlane = plane;
        }
      }
    }
  }

  Choice choice;
  double bestPolygon = kInfinity;
  bool bestOneSided = false;
  const std::uint32_t listCandidates =
    n <= Effort.extraCandidateList ? candidates * Effort.candidateFactor : candidates;
  const std::uint32_t polygonCandidates = std::min(listCandidates, n);
  for (std::uint32_t c = 0; c < polygonCandidates; ++c)
  {
    const std::uint32_t index = n <= listCandidates ? c : rng.below(n);
    const std::uint32_t piece = list[index].piece;
    const glm::dvec4& plane = Planes[piece];
    const double sc = score(plane, piece, std::min(bestPolygon, bestFree));
    if (sc < bestPolygon || choice.piece == kNone)
    {
      bestPolygon = std::min(bestPolygon, sc);
      choice.plane = plane;
      choice.piece = piece;
      bestOneSided = oneSided && sc < kInfinity;
    }
  }
  choice.fallbackPlane = choice.plane;
  choice.fallbackPiece = choice.piece;

  // A one-sided polygon plane peels off a single polygon; on a long list that is a chain as deep
  // as the list, so any separating free plane is preferred there.
  const bool chainTooLong = bestOneSided && n > kMaxChainList;
  if (bestFree < kInfinity && (bestFree < bestPolygon || chainTooLong))
  {
    choice.plane = freePlane;
    choice.piece = kNone;
  }
  return choice;
}

/// Bounds of the points of polygons that can take part (finite, in range, >= 3 distinct ids).
/// Unused points and points of dropped polygons must not set the origin or the tolerance: one
/// stray point 1e7 away would otherwise make the tolerance swallow real features (fuzzer finding
/// "stray-point-inflates-tolerance").
Box usableBounds(const PolygonMesh& mesh)
{
  Box box;
  const std::size_t numPoints = mesh.points.size();
  for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
  {
    const std::uint32_t* ids = mesh.polygon(i);
    const std::uint32_t count = mesh.polygonSize(i);
    bool usable = count >= 3;
    std::uint32_t distinct = 0;
    for (std::uint32_t k = 0; k < count && usable; ++k)
    {
      usable = ids[k] < numPoints && std::isfinite(mesh.points[ids[k]].x) &&
        std::isfinite(mesh.points[ids[k]].y) && std::isfinite(mesh.points[ids[k]].z);
      distinct += (k == 0 || ids[k] != ids[k - 1]) ? 1 : 0;
    }
    if (usable && distinct >= 3)
    {
      for (std::uint32_t k = 0; k < count; ++k)
      {
        box.extend(mesh.points[ids[k]]);
      }
    }
  }
  return box;
}

Tree Builder::run()
{
  const auto startTime = std::chrono::steady_clock::now();
  BuildStatistics& st = Out.statistics;
  st.inputPolygons = Mesh.polygonCount();

  const Box bounds = usableBounds(Mesh);
  Out.origin = bounds.empty() ? glm::dvec3(0.0) : bounds.center();
  const double diagonal = bounds.diagonal();
  // The larger of the requested tolerance and the coordinate resolution (kResolutionSteps): far
  // from the origin the rounding of the coordinates themselves can exceed a small scene's
  // relative tolerance, and planar polygons would then be triangulated.
  const double maxCoordinate = bounds.empty() ? 0.0
                                              : std::max({ std::abs(bounds.lo.x), std::abs(bounds.lo.y),
                                                  std::abs(bounds.lo.z), std::abs(bounds.hi.x),
                                                  std::abs(bounds.hi.y), std::abs(bounds.hi.z) });
  Tol = std::max(Config.relativeTolerance * (diagonal > 0.0 ? diagonal : 1.0),
    kResolutionSteps * std::numeric_limits<double>::epsilon() * maxCoordinate);
  Out.tolerance = st.tolerance = Tol;
  Out.points = Mesh.points;
  Out.inputPointCount = Mesh.points.size();
  Local.resize(Mesh.points.size());
  for (std::size_t i = 0; i < Local.size(); ++i)
  {
    Local[i] = Mesh.points[i] - Out.origin;
  }

  {
    scenevis::detail::PolygonPieces input;
    scenevis::detail::PieceCounts counts;
    scenevis::detail::splitIntoPieces(Mesh, Local, Tol, input, counts);
    st.invalidPolygons += counts.invalid;
    st.degeneratePolygons += counts.degenerate;
    st.triangulatedPolygons += counts.triangulated;
    PiecePlane = std::move(input.plane);
    PieceSource = std::move(input.source);
    PieceCount = std::move(input.count);
    Verts = std::move(input.verts);
  }
  const auto pieces = static_cast<std::uint32_t>(PieceSource.size());
  Arena.reserve(pieces + pieces / 4);
  {
    std::uint32_t first = 0;
    for (std::uint32_t p = 0; p < pieces; ++p)
    {
      const std::uint32_t count = PieceCount[p];
      Arena.push_back(Frag{ p, first, count });
      first += count;
    }
  }

  Out.nodes.reserve(pieces + pieces / 2);
  Out.fragments.reserve(pieces + pieces / 4);
  Out.fragmentVertices.reserve(Verts.size() + Verts.size() / 4);

  Planes = PiecePlane.data();
  Sources = PieceSource.data();
  Scored = Config.partition == BuildConfig::Partition::Scored;
  Threads = Config.threads > 0 ? static_cast<unsigned>(Config.threads)
                               : std::max(1u, std::thread::hardware_concurrency());
  Cancel = &CancelFlag;
  std::vector<Task> tasks;
  if (pieces > 0)
  {
    std::uint64_t seedState = Config.seed;
    tasks.push_back(Task{ 0, pieces, kNone, 1, splitmix64(seedState), false, false });
  }
  const std::size_t reportStep = std::max<std::size_t>(1, pieces / 100);
  std::size_t nextReport = reportStep;
  bool cancelled = false;
  try
  {
    for (;;)
    {
      if (Worker && tasks.size() == ForkStack)
      {
        join(); // everything the serial build does before the worker's subtree is done
      }
      if (tasks.empty())
      {
        break;
      }
      const Task task = tasks.back();
      tasks.pop_back();
      step(task, tasks);
      if (Progress && Placed >= nextReport)
      {
        nextReport = Placed + reportStep;
        if (!Progress(std::min(1.0, static_cast<double>(Placed) / pieces)))
        {
          cancelled = true;
          break;
        }
      }
    }
  }
  catch (...)
  {
    CancelFlag = true;
    if (WorkerThread.joinable())
    {
      WorkerThread.join();
    }
    throw;
  }
  if (cancelled)
  {
    CancelFlag = true;
    if (WorkerThread.joinable())
    {
      WorkerThread.join();
    }
    Tree empty;
    empty.statistics.inputPolygons = st.inputPolygons;
    return empty;
  }

  if (Config.conformingFragments)
  {
    st.conformingVertices = makeConforming(Out);
  }
  Out.nodes.shrink_to_fit();
  Out.fragments.shrink_to_fit();
  Out.fragmentVertices.shrink_to_fit();
  Out.points.shrink_to_fit();
  Out.splitPoints.shrink_to_fit();
  Out.leaves.shrink_to_fit();
  Out.leafPlanes.shrink_to_fit();
  Out.leafPairs.shrink_to_fit();
  st.nodes = Out.nodes.size();
  st.fragments = Out.fragments.size();
  st.orderedLeaves = Out.leaves.size();
  st.leafPairs = Out.leafPairs.size();
  st.fragmentsWithoutFallbacks = st.fragments - FallbackFragments;
  st.memoryBytes = Out.nodes.capacity() * sizeof(Node) +
    Out.fragments.capacity() * sizeof(Fragment) +
    Out.fragmentVertices.capacity() * sizeof(std::uint32_t) +
    Out.points.capacity() * sizeof(glm::dvec3) + Out.splitPoints.capacity() * sizeof(SplitPoint) +
    Out.leaves.capacity() * sizeof(OrderedLeaf) + Out.leafPlanes.capacity() * sizeof(glm::dvec4) +
    Out.leafPairs.capacity() * sizeof(LeafPair);
  st.buildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
  return std::move(Out);
}

void Builder::step(const Task& task, std::vector<Task>& tasks)
{
  BuildStatistics& st = Out.statistics;
  const std::uint32_t n = task.end - task.begin;
  // At leaf size, a plane that splits none of the list comes first: a polygon's, else (for a
  // list that could be a leaf needing a fallback) an axis-aligned plane through a gap or one of
  // the pairs' separating planes (makeLeaf). Such a node orders its sides exactly with no sort
  // and needs no fallback; only what cannot be partitioned that way becomes an ordered leaf.
  std::uint32_t peel = kNone;
  bool separate = false;
  glm::dvec4 separating;
  if (n <= std::min(Config.orderedLeafSize, kMaxLeafPolygons))
  {
    peel = splitFreePiece(task);
    if (peel == kNone && !task.noLeaf)
    {
      const LeafResult result = makeLeaf(task, tasks, separating);
      if (result == LeafResult::Made)
      {
        return;
      }
      separate = result == LeafResult::Separate;
    }
  }

  glm::dvec4 plane;
  std::uint32_t piece;
  Choice choice;
  if (peel != kNone)
  {
    piece = peel;
    plane = Planes[piece];
  }
  else if (separate)
  {
    piece = kNone;
    plane = separating;
  }
  else if (!Scored || (task.oneSidedRun && n <= kMinFreePlaneList))
  {
    piece = Arena[task.begin].piece;
    plane = Planes[piece];
  }
  else
  {
    choice = chooseScored(task, n);
    piece = choice.piece;
    plane = choice.plane;
  }

  // Full classification first, so that a free plane that separates nothing can still be
  // replaced by a polygon plane before anything is split.
  std::uint32_t nFront = 0;
  std::uint32_t nBack = 0;
  std::uint32_t nSplit = 0;
  std::uint32_t nOn = 0;
  Codes.resize(n);
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    nFront = nBack = nSplit = nOn = 0;
    for (std::uint32_t i = 0; i < n; ++i)
    {
      const Frag& f = Arena[task.begin + i];
      // The partition polygon's own fragments are on its plane by construction; forcing it
      // guarantees progress even if rounding put a vertex a hair outside the tolerance.
      const Side side = f.piece == piece ? On : classify(plane, f);
      Codes[i] = side;
      nFront += side == Front;
      nBack += side == Back;
      nSplit += side == Straddle;
      nOn += side == On;
    }
    if (piece != kNone)
    {
      break;
    }
    // Free plane: coplanar fragments go behind. Both children must be strictly smaller than
    // this list, or the build would not terminate.
    if (nFront + nSplit < n && nBack + nOn + nSplit < n)
    {
      break;
    }
    piece = choice.fallbackPiece;
    plane = choice.fallbackPlane;
  }

  const auto nodeIndex = static_cast<std::uint32_t>(Out.nodes.size());
  Node node;
  node.plane = plane;
  node.firstFragment = static_cast<std::uint32_t>(Out.fragments.size());
  Out.nodes.push_back(node);
  link(task, nodeIndex);
  st.depth = std::max<std::size_t>(st.depth, task.depth);
  if (piece == kNone)
  {
    ++st.freePlaneNodes;
  }

  Cache.clear();
  FrontScratch.clear();
  OwnScratch.clear();
  std::uint32_t write = task.begin;
  for (std::uint32_t i = 0; i < n; ++i)
  {
    const Frag f = Arena[task.begin + i];
    switch (Codes[i])
    {
      case On:
        if (piece == kNone)
        {
          Arena[write++] = f;
        }
        else
        {
          OwnScratch.push_back(f);
        }
        break;
      case Back:
        Arena[write++] = f;
        break;
      case Front:
        FrontScratch.push_back(f);
        break;
      default:
      {
        Frag front;
        Frag back;
        split(f, plane, front, back);
        Arena[write++] = back;
        FrontScratch.push_back(front);
        ++st.splits;
        break;
      }
    }
  }
  const std::uint32_t backEnd = write;
  Arena.resize(backEnd);
  Arena.insert(Arena.end(), FrontScratch.begin(), FrontScratch.end());
  const auto frontEnd = static_cast<std::uint32_t>(Arena.size());

  std::sort(OwnScratch.begin(), OwnScratch.end(),
    [](const Frag& a, const Frag& b) { return a.piece < b.piece; });
  for (const Frag& f : OwnScratch)
  {
    Out.fragments.push_back(Fragment{ Sources[f.piece],
      static_cast<std::uint32_t>(Out.fragmentVertices.size()), f.count });
    Out.fragmentVertices.insert(
      Out.fragmentVertices.end(), Verts.begin() + f.first, Verts.begin() + f.first + f.count);
  }
  Out.nodes[nodeIndex].fragmentCount = static_cast<std::uint32_t>(OwnScratch.size());
  if (task.noLeaf)
  {
    FallbackFragments += OwnScratch.size();
  }

  // A polygon plane with everything on one side and nothing split means a locally convex (or
  // concave) patch: its remaining polygons will keep doing that, and free planes have already
  // lost here, so the child skips scoring and chains. The run ends at the first node where the
  // one-sidedness fails.
  const bool oneSided =
    Scored && piece != kNone && nSplit == 0 && (nFront == 0 || nBack == 0);
  const Task backTask{ task.begin, backEnd, nodeIndex, task.depth + 1, childKey(task.key, false),
    false, oneSided, task.noLeaf };
  if (parallel() && !Worker && backEnd - task.begin >= kMinParallelList &&
    frontEnd - backEnd >= kMinParallelList)
  {
    // The serial build would do the whole front subtree, then this back subtree: the worker
    // builds the latter meanwhile, and join() appends it once the stack is back to this size.
    ForkStack = tasks.size();
    fork(backTask);
  }
  else if (backEnd > task.begin)
  {
    tasks.push_back(backTask);
  }
  if (frontEnd > backEnd)
  {
    tasks.push_back(Task{ backEnd, frontEnd, nodeIndex, task.depth + 1, childKey(task.key, true),
      true, oneSided, task.noLeaf });
  }
  if (!task.noLeaf)
  {
    Placed += OwnScratch.size();
  }
}

void Builder::link(const Task& task, std::uint32_t reference)
{
  if (task.parent == kNone)
  {
    Out.root = reference;
  }
  else if (isLeaf(task.parent))
  {
    Out.leaves[task.parent & ~kLeafBit].fallback = reference;
  }
  else
  {
    (task.isFront ? Out.nodes[task.parent].front : Out.nodes[task.parent].back) = reference;
  }
}

std::uint32_t Builder::splitFreePiece(const Task& task) const
{
  const Frag* list = Arena.data() + task.begin;
  const std::uint32_t n = task.end - task.begin;
  for (std::uint32_t i = 0; i < n; ++i)
  {
    const std::uint32_t piece = list[i].piece;
    const glm::dvec4& plane = Planes[piece];
    bool splits = false;
    for (std::uint32_t j = 0; j < n && !splits; ++j)
    {
      splits = list[j].piece != piece && classify(plane, list[j]) == Straddle;
    }
    if (!splits)
    {
      return piece;
    }
  }
  return kNone;
}

bool Builder::gapPlane(const Frag* list, std::uint32_t n, glm::dvec4& plane)
{
  std::uint32_t bestBalance = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    GapScratch.clear();
    for (std::uint32_t i = 0; i < n; ++i)
    {
      double lo = std::numeric_limits<double>::infinity();
      double hi = -lo;
      for (std::uint32_t k = 0; k < list[i].count; ++k)
      {
        const double x = Local[Verts[list[i].first + k]][axis];
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      GapScratch.emplace_back(lo, hi);
    }
    std::sort(GapScratch.begin(), GapScratch.end());
    double reach = GapScratch[0].second; // the highest extent so far
    for (std::uint32_t k = 1; k < n; ++k)
    {
      const double next = GapScratch[k].first;
      const std::uint32_t balance = std::min(k, n - k);
      if (next >= reach - Tol && balance > bestBalance)
      {
        // Everything before k reaches at most `reach`, everything after starts at `next` or
        // later: the plane between them has each within Tol/2 of its side.
        glm::dvec4 candidate(0.0);
        candidate[axis] = 1.0;
        candidate.w = -0.5 * (reach + next);
        bestBalance = balance;
        plane = candidate;
      }
      reach = std::max(reach, GapScratch[k].second);
    }
  }
  if (bestBalance == 0)
  {
    return false;
  }
  // Checked as the partition will classify it (the sweep's reasoning is only within Tol).
  std::uint32_t front = 0;
  for (std::uint32_t i = 0; i < n; ++i)
  {
    const Side side = classify(plane, list[i]);
    if (side == Straddle)
    {
      return false;
    }
    front += side == Front;
  }
  return front > 0 && front < n;
}

Builder::LeafResult Builder::makeLeaf(
  const Task& task, std::vector<Task>& tasks, glm::dvec4& separating)
{
  const std::uint32_t n = task.end - task.begin;
  const Frag* list = Arena.data() + task.begin;
  if (!Leaf.analyse(geometry(), list, n))
  {
    return LeafResult::Split;
  }
  if (Leaf.mayCycle && gapPlane(list, n, separating))
  {
    return LeafResult::Separate;
  }
  if (Leaf.mayCycle)
  {
    // A fallback would be needed: first try a gap between the fragments along an axis (above),
    // then the pairs' other separating planes (evenly sampled) as a partition with fragments on
    // both sides and none split.
    const auto extra = static_cast<std::uint32_t>(Leaf.planes.size()) - n;
    const std::uint32_t stride = std::max(1u, extra / kSeparatingTries);
    for (std::uint32_t p = n; p < Leaf.planes.size(); p += stride)
    {
      const glm::dvec4& plane = Leaf.planes[p];
      std::uint32_t front = 0;
      std::uint32_t back = 0;
      bool splits = false;
      for (std::uint32_t j = 0; j < n && !splits; ++j)
      {
        const Side side = classify(plane, list[j]);
        splits = side == Straddle;
        front += side == Front;
        back += side != Front;
      }
      if (!splits && front > 0 && back > 0)
      {
        separating = plane;
        return LeafResult::Separate;
      }
    }
  }
  const std::vector<glm::dvec4>& leafPlanes = Leaf.planes;
  const std::vector<LeafPair>& leafPairs = Leaf.pairs;
  const bool mayCycle = Leaf.mayCycle;

  const auto leafIndex = static_cast<std::uint32_t>(Out.leaves.size());
  OrderedLeaf leaf;
  leaf.firstFragment = static_cast<std::uint32_t>(Out.fragments.size());
  leaf.fragmentCount = n;
  leaf.firstPlane = static_cast<std::uint32_t>(Out.leafPlanes.size());
  leaf.planeCount = static_cast<std::uint32_t>(leafPlanes.size());
  leaf.firstPair = static_cast<std::uint32_t>(Out.leafPairs.size());
  leaf.pairCount = static_cast<std::uint32_t>(leafPairs.size());
  Out.leaves.push_back(leaf);
  link(task, kLeafBit | leafIndex);
  for (std::uint32_t i = 0; i < n; ++i)
  {
    const Frag& f = list[i];
    Out.fragments.push_back(Fragment{
      Sources[f.piece], static_cast<std::uint32_t>(Out.fragmentVertices.size()), f.count });
    Out.fragmentVertices.insert(
      Out.fragmentVertices.end(), Verts.begin() + f.first, Verts.begin() + f.first + f.count);
  }
  Out.leafPlanes.insert(Out.leafPlanes.end(), leafPlanes.begin(), leafPlanes.end());
  Out.leafPairs.insert(Out.leafPairs.end(), leafPairs.begin(), leafPairs.end());
  BuildStatistics& st = Out.statistics;
  st.leafFragments += n;
  st.depth = std::max<std::size_t>(st.depth, task.depth);
  Placed += n;
  if (mayCycle)
  {
    // The same list, split as usual, for the eyes that see a cycle. Placed counts input work, so
    // the fallback's fragments are not counted twice (see step()).
    Task fallback = task;
    fallback.parent = kLeafBit | leafIndex;
    fallback.depth = task.depth + 1;
    fallback.noLeaf = true;
    tasks.push_back(fallback);
  }
  else
  {
    Arena.resize(task.begin);
  }
  return LeafResult::Made;
}

void Builder::fork(const Task& task)
{
  ForkNode = task.parent;
  ForkPoints = Out.points.size();
  static const ProgressCallback noProgress; // the worker never reports; join() counts its work
  Worker = std::make_unique<Builder>(Mesh, Config, noProgress);
  Builder& w = *Worker;
  w.Out.origin = Out.origin;
  w.Out.tolerance = Out.tolerance;
  w.Out.inputPointCount = Out.inputPointCount;
  w.Tol = Tol;
  w.Planes = Planes;
  w.Sources = Sources;
  w.Scored = Scored;
  w.Cancel = Cancel;
  // Copies: this builder keeps appending to its own arrays while the worker runs.
  w.Local = Local;
  w.Out.points = Out.points;
  const std::uint32_t n = task.end - task.begin;
  w.Arena.reserve(n + n / 4);
  w.Verts.reserve(static_cast<std::size_t>(n) * 4);
  for (std::uint32_t i = task.begin; i < task.end; ++i)
  {
    Frag f = Arena[i];
    const auto first = static_cast<std::uint32_t>(w.Verts.size());
    w.Verts.insert(w.Verts.end(), Verts.begin() + f.first, Verts.begin() + f.first + f.count);
    f.first = first;
    w.Arena.push_back(f);
  }
  w.Out.nodes.reserve(n + n / 2);
  w.Out.fragments.reserve(n + n / 4);
  Task root = task;
  root.begin = 0;
  root.end = n;
  root.parent = kNone;
  WorkerThread = std::thread(
    [&w, root]()
    {
      try
      {
        std::vector<Task> tasks{ root };
        while (!tasks.empty() && !w.Cancel->load(std::memory_order_relaxed))
        {
          const Task t = tasks.back();
          tasks.pop_back();
          w.step(t, tasks);
        }
      }
      catch (...)
      {
        w.WorkerError = std::current_exception();
      }
    });
}

void Builder::join()
{
  WorkerThread.join();
  std::unique_ptr<Builder> worker = std::move(Worker);
  if (worker->WorkerError)
  {
    std::rethrow_exception(worker->WorkerError);
  }
  Tree& w = worker->Out;
  // Point ids: the worker numbered its split points from ForkPoints on; here they follow the
  // ones made since the fork, exactly where the serial build would have made them.
  const std::size_t shift = Out.points.size() - ForkPoints;
  const auto fork = static_cast<std::uint32_t>(ForkPoints);
  auto remap = [fork, shift](std::uint32_t id)
  { return id >= fork ? static_cast<std::uint32_t>(id + shift) : id; };
  const auto nodeOffset = static_cast<std::uint32_t>(Out.nodes.size());
  const auto fragmentOffset = static_cast<std::uint32_t>(Out.fragments.size());
  const auto vertexOffset = static_cast<std::uint32_t>(Out.fragmentVertices.size());
  const auto leafOffset = static_cast<std::uint32_t>(Out.leaves.size());
  const auto planeOffset = static_cast<std::uint32_t>(Out.leafPlanes.size());
  const auto pairOffset = static_cast<std::uint32_t>(Out.leafPairs.size());
  // A child reference is a node or (kLeafBit) a leaf; each kind moves by its own offset.
  auto moved = [nodeOffset, leafOffset](std::uint32_t reference)
  {
    if (reference == kNone)
    {
      return kNone;
    }
    return isLeaf(reference) ? reference + leafOffset : reference + nodeOffset;
  };
  (ForkNode != kNone ? Out.nodes[ForkNode].back : Out.root) = moved(w.root);
  for (Node node : w.nodes)
  {
    node.front = moved(node.front);
    node.back = moved(node.back);
    node.firstFragment += fragmentOffset;
    Out.nodes.push_back(node);
  }
  for (OrderedLeaf leaf : w.leaves)
  {
    leaf.firstFragment += fragmentOffset;
    leaf.firstPlane += planeOffset;
    leaf.firstPair += pairOffset;
    leaf.fallback = moved(leaf.fallback);
    Out.leaves.push_back(leaf);
  }
  Out.leafPlanes.insert(Out.leafPlanes.end(), w.leafPlanes.begin(), w.leafPlanes.end());
  Out.leafPairs.insert(Out.leafPairs.end(), w.leafPairs.begin(), w.leafPairs.end());
  for (Fragment f : w.fragments)
  {
    f.first += vertexOffset;
    Out.fragments.push_back(f);
  }
  Out.fragmentVertices.reserve(Out.fragmentVertices.size() + w.fragmentVertices.size());
  for (std::uint32_t id : w.fragmentVertices)
  {
    Out.fragmentVertices.push_back(remap(id));
  }
  Out.points.insert(Out.points.end(), w.points.begin() + ForkPoints, w.points.end());
  Local.insert(Local.end(), worker->Local.begin() + ForkPoints, worker->Local.end());
  for (SplitPoint sp : w.splitPoints)
  {
    Out.splitPoints.push_back(SplitPoint{ remap(sp.a), remap(sp.b), sp.t });
  }
  BuildStatistics& st = Out.statistics;
  st.depth = std::max(st.depth, w.statistics.depth);
  st.freePlaneNodes += w.statistics.freePlaneNodes;
  st.splits += w.statistics.splits;
  st.leafFragments += w.statistics.leafFragments;
  FallbackFragments += worker->FallbackFragments;
  Placed += worker->Placed;
}

} // namespace

Tree build(const PolygonMesh& mesh, const BuildConfig& config, const ProgressCallback& progress)
{
  return Builder(mesh, config, progress).run();
}

} // namespace bsp
} // namespace scenevis
