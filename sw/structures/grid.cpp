// The uniform grid (lecture 3, "Uniform Grids"): one level of cubical cells
// over the kd-tree's scene box, n^3 = d |O| of them, each listing the
// triangles it overlaps; rays walk it with the 3D-DDA and a mailbox keeps a
// triangle listed in several cells from being tested twice.

#include "structures/grid_level.h"
#include "structures/structure.h"

namespace kdrt {
namespace {

class Grid : public StructureBase<Grid>, public grid::CellsView {
 public:
  Grid(const StructureInput& input, const StructureOptions& options) : StructureBase(input) { Build(options); }

  AccelKind kind() const override { return AccelKind::kGrid; }
  bool uses_mailbox() const override { return true; }

  template <class A>
  void TraceT(const A& a, const RaySetup<A>& r, Query query, TraceResult<A>& best, TraceScratch& scratch) const {
    if (cells_.empty) return;
    const BoxClip<A> clip = ClipToBox(a, r, input_->bounds.lo, input_->bounds.hi);
    if (clip.miss) return;
    grid::WalkLevel(a, r, cells_.levels[0], cells_.planes.data(), clip.t0, clip.t1,
                    [&](uint32_t cell, typename A::T, typename A::T t_exit) {
                      grid::TestCellList(a, r, cells_, *input_, cell, best, scratch);
                      return DoneAfterCell(a, best, query, t_exit);
                    });
  }

 private:
  void Build(const StructureOptions& options) {
    const StructureInput& in = *input_;
    const accel::Box& b = in.bounds;
    grid::Resolution res;
    cells_.empty = !grid::ValidBox(b);
    if (!cells_.empty) res = grid::ResolutionForBox(b.lo, b.hi, in.ids.size(), options.grid_density);
    const grid::Level level = grid::MakeLevel(b.lo, b.hi, res, 0, &cells_.planes);
    cells_.levels.push_back(level);
    if (!cells_.empty) {
      grid::CellLists lists = grid::BinAll(level, cells_.planes.data(), in, in.ids.data(), in.ids.size(),
                                                 grid::BinningMargin(b));
      cells_.begin = std::move(lists.begin);
      cells_.refs = std::move(lists.refs);
    } else {
      cells_.begin.assign(size_t(level.cells()) + 1, 0);
    }
    grid::FillCellStats(cells_, &stats_);
    stats_.max_depth = 0;
    stats_.extra["resolution"] = {level.n[0], level.n[1], level.n[2]};
    stats_.extra["density"] = options.grid_density;
    if (res.clamped) stats_.extra["clamped"] = true;
  }
};

}  // namespace

std::unique_ptr<Structure> BuildGrid(const StructureInput& input, const StructureOptions& options) {
  CheckStructureOptions(options);
  return Structure::Timed([&] { return std::make_unique<Grid>(input, options); });
}

}  // namespace kdrt
