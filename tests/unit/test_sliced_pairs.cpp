// The sliced pair layout (kernels/neighbors/sliced_pairs.hpp, issue 24 item
// 3) against the compressed rows it is built from: every row reads the same
// pairs, with the same data, in the same order, through PairList::row; the
// k-th pairs of a slice's rows are adjacent (what makes a warp's loads
// coalesced); slices are as wide as their longest row; a height of 1 is the
// compressed layout itself.
#include <gtest/gtest.h>

#include "kernels/neighbors/sliced_pairs.hpp"
#include "particle_fixture.hpp"

using namespace mfsd;

namespace {

template <int D>
void sliced_rows_read_the_compressed_pairs(Index height, bool beta) {
  const int n[3] = {13, 7, 5};  // 455 or 91 particles: the last slice is partial
  const double dp = 0.01;
  const auto x = test::lattice<D>(n, dp, 0.2, 9);
  test::Fixture<D, double> c(x, dp, 1.3 * dp, true, {}, beta);
  test::Fixture<D, double> s(x, dp, 1.3 * dp, true, {}, beta);
  const Index m = Index(x.size());
  const double padding = make_sliced_layout(s.pairs, m, height);
  EXPECT_EQ(s.pairs.slice_height, height);
  EXPECT_GE(padding, 1.0);
  const auto cv = c.pairs.view(), sv = s.pairs.view();
  EXPECT_EQ(sv.stride, height);
  const auto cn = to_host<Cpu>(c.pairs.neighbor), sn = to_host<Cpu>(s.pairs.neighbor);
  const auto cg = to_host<Cpu>(c.pairs.grad), sg = to_host<Cpu>(s.pairs.grad);
  const auto cs = to_host<Cpu>(c.pairs.stretch), ss = to_host<Cpu>(s.pairs.stretch);
  const auto cb = to_host<Cpu>(c.pairs.beta), sb = to_host<Cpu>(s.pairs.beta);
  size_t stored = 0;
  for (Index slice = 0; slice * height < m; ++slice) {
    Index width = 0;
    for (Index i = slice * height; i < std::min(m, (slice + 1) * height); ++i) width = std::max(width, cv.row(i).count);
    stored += size_t(width) * size_t(height);
  }
  EXPECT_EQ(sg.size(), stored);  // each slice as wide as its longest row
  EXPECT_DOUBLE_EQ(padding, double(stored) / double(c.pairs.pairs()));
  EXPECT_GE(sn.size(), stored + size_t(kPairPrefetchDistance) * size_t(height));  // the prefetch's reach
  for (Index i = 0; i < m; ++i) {
    const PairRow a = cv.row(i), b = sv.row(i);
    ASSERT_EQ(a.count, b.count) << i;
    EXPECT_EQ(b.stride, height);
    if (i % height) EXPECT_EQ(b.first, sv.row(i - 1).first + 1) << i;  // adjacent k-th pairs
    for (Index k = 0; k < a.count; ++k) {
      const PairIndex p = a.at(k), q = b.at(k);
      ASSERT_LT(size_t(q), sg.size());
      EXPECT_EQ(cn[size_t(p)], sn[size_t(q)]);
      EXPECT_EQ(cs[size_t(p)], ss[size_t(q)]);
      for (int d = 0; d < D; ++d) EXPECT_EQ(cg[size_t(p)].v[d], sg[size_t(q)].v[d]);
      if (beta) EXPECT_EQ(cb[size_t(p)], sb[size_t(q)]);
    }
  }
}

TEST(SlicedPairs, RowsReadTheCompressedPairs3D) { sliced_rows_read_the_compressed_pairs<3>(kSliceHeight, false); }
TEST(SlicedPairs, RowsReadTheCompressedPairs2DWithBeta) {
  sliced_rows_read_the_compressed_pairs<2>(kSliceHeight, true);
}
TEST(SlicedPairs, OddHeights) {
  sliced_rows_read_the_compressed_pairs<3>(7, false);
  sliced_rows_read_the_compressed_pairs<2>(1000, false);  // one slice
}

TEST(SlicedPairs, HeightOneIsTheCompressedLayout) {
  const int n[3] = {6, 5, 4};
  const auto x = test::lattice<3>(n, 0.01, 0.2, 2);
  test::Fixture<3, double> c(x, 0.01, 0.013, true), s(x, 0.01, 0.013, true);
  EXPECT_DOUBLE_EQ(make_sliced_layout(s.pairs, Index(x.size()), 1), 1.0);
  const auto a = to_host<Cpu>(c.pairs.grad), b = to_host<Cpu>(s.pairs.grad);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].v[0], b[k].v[0]);
}

TEST(SlicedPairs, NeedsCompressedFullRows) {
  const int n[3] = {5, 5, 5};
  const auto x = test::lattice<3>(n, 0.01, 0.0, 1);
  test::Fixture<3, double> f(x, 0.01, 0.013, true);
  make_sliced_layout(f.pairs, Index(x.size()), 4);
  EXPECT_THROW(make_sliced_layout(f.pairs, Index(x.size()), 4), std::logic_error);  // already sliced
  test::Fixture<3, double> g(x, 0.01, 0.013, true);
  g.pairs.release_full_rows();
  EXPECT_THROW(make_sliced_layout(g.pairs, Index(x.size()), 4), std::logic_error);
  test::Fixture<3, double> h(x, 0.01, 0.013, true);
  EXPECT_THROW(make_sliced_layout(h.pairs, Index(x.size()), 0), std::logic_error);
}

}  // namespace
