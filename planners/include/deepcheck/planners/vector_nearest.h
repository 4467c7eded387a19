#pragma once
// VectorNearest: the nearest neighbours of a tree planner's motions in a RealVectorStateSpace, by
// the space's own distance (Euclidean), found by scanning coordinates stored one array per
// dimension.
//
// OMPL's default for tree planners, GNAT, calls the distance function (a std::function, then a
// virtual call of the state space) on every element it visits, and on the trees of a planner that
// solves in a millisecond (tens to hundreds of motions) it visits nearly all of them. Here a query
// is a loop over each dimension's array that the compiler vectorizes, then a scan for the
// smallest. Once the tree holds kScanLimit elements (or the limit given) they move into a GNAT,
// which answers from then on with the planner's distance function.
//
// T is a pointer to an object whose `state` is a RealVectorStateSpace state of `dimension` values
// (the Motion of OMPL's tree planners). The distance function the planner sets must be that
// space's distance: makePlanner (planner_factory.h) uses VectorNearest only then. Answers are the
// nearest by that distance (up to its rounding); among equally near elements the one added first.
// Like OMPL's GNATNoThreadSafety, one thread at a time.

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsGNATNoThreadSafety.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace deepcheck::planners {

template <typename T>
class VectorNearest : public ompl::NearestNeighbors<T> {
 public:
  /// Elements held before they move into a GNAT. On the Panda's 7 joints a scan stays faster than
  /// GNAT's query up to the largest tree bench/nearest_bench measures (16384 uniform samples),
  /// since in 7 dimensions GNAT prunes little; past this many a scan takes a few hundred
  /// microseconds, and GNAT's pruning of a tree's clustered nodes bounds the cost.
  static constexpr std::size_t kScanLimit = std::size_t{1} << 16;

  /// `scanLimit`: the elements held before they move into a GNAT (at least 1).
  explicit VectorNearest(unsigned dimension, std::size_t scanLimit = kScanLimit)
      : dimension_(dimension),
        scanLimit_(scanLimit),
        coordinates_(dimension),
        last_(dimension, std::numeric_limits<double>::quiet_NaN()) {
    if (dimension == 0) throw std::invalid_argument("VectorNearest: the dimension must be at least 1");
    if (scanLimit == 0) throw std::invalid_argument("VectorNearest: the scan limit must be at least 1");
  }

  void setDistanceFunction(const typename ompl::NearestNeighbors<T>::DistanceFunction& distance) override {
    ompl::NearestNeighbors<T>::setDistanceFunction(distance);
    if (tree_) tree_->setDistanceFunction(distance);
  }

  bool reportsSortedResults() const override { return true; }

  void clear() override {
    forgetQuery();
    tree_.reset();
    elements_.clear();
    for (std::vector<double>& c : coordinates_) c.clear();
  }

  void add(const T& element) override {
    if (tree_) {
      tree_->add(element);
      return;
    }
    elements_.push_back(element);
    const double* x = valuesOf(element);
    for (unsigned d = 0; d < dimension_; ++d) coordinates_[d].push_back(x[d]);
    if (elements_.size() >= scanLimit_) moveToTree();
  }

  bool remove(const T& element) override {
    if (tree_) return tree_->remove(element);
    const auto it = std::find(elements_.begin(), elements_.end(), element);
    if (it == elements_.end()) return false;
    const auto i = it - elements_.begin();
    forgetQuery();
    elements_.erase(it);
    for (std::vector<double>& c : coordinates_) c.erase(c.begin() + i);
    return true;
  }

  /// The same query again (equal values) after elements were only added scans only the new ones:
  /// RRTConnect's connect steps ask for the nearest to one state after each step it adds.
  T nearest(const T& query) const override {
    if (tree_) return tree_->nearest(query);
    if (elements_.empty()) throw ompl::Exception("VectorNearest: no elements to search");
    const double* q = valuesOf(query);
    std::size_t from = scanned_;
    if (!std::equal(q, q + dimension_, last_.begin())) {
      std::copy(q, q + dimension_, last_.begin());
      from = 0;
    }
    squaredDistances(q, from);
    const std::size_t n = elements_.size();
    const double* s = squared_.data();
    std::size_t best = from == 0 ? 0 : best_;
    double bestSquared = from == 0 ? s[0] : bestSquared_;
    for (std::size_t i = std::max<std::size_t>(from, 1); i < n; ++i) {
      if (s[i] < bestSquared) {
        best = i;
        bestSquared = s[i];
      }
    }
    best_ = best;
    bestSquared_ = bestSquared;
    scanned_ = n;
    return elements_[best];
  }

  void nearestK(const T& query, std::size_t k, std::vector<T>& found) const override {
    if (tree_) return tree_->nearestK(query, k, found);
    found.clear();
    if (elements_.empty() || k == 0) return;
    squaredDistances(valuesOf(query), 0);
    order_.resize(elements_.size());
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    const std::size_t kept = std::min(k, order_.size());
    std::partial_sort(order_.begin(), order_.begin() + static_cast<std::ptrdiff_t>(kept), order_.end(),
                      [this](std::size_t a, std::size_t b) { return closer(a, b); });
    for (std::size_t j = 0; j < kept; ++j) found.push_back(elements_[order_[j]]);
  }

  void nearestR(const T& query, double radius, std::vector<T>& found) const override {
    if (tree_) return tree_->nearestR(query, radius, found);
    found.clear();
    if (elements_.empty()) return;
    squaredDistances(valuesOf(query), 0);
    order_.clear();
    for (std::size_t i = 0; i < elements_.size(); ++i) {
      if (std::sqrt(squared_[i]) <= radius) order_.push_back(i);
    }
    std::sort(order_.begin(), order_.end(), [this](std::size_t a, std::size_t b) { return closer(a, b); });
    for (std::size_t i : order_) found.push_back(elements_[i]);
  }

  std::size_t size() const override { return tree_ ? tree_->size() : elements_.size(); }

  void list(std::vector<T>& all) const override {
    if (tree_) return tree_->list(all);
    all = elements_;
  }

 private:
  static const double* valuesOf(const T& element) {
    return element->state->template as<ompl::base::RealVectorStateSpace::StateType>()->values;
  }

  /// Nearer, or as near and added earlier.
  bool closer(std::size_t a, std::size_t b) const {
    return squared_[a] < squared_[b] || (squared_[a] == squared_[b] && a < b);
  }

  /// squared_[i] for i >= from: the squared distance of element i from q (the entries before
  /// are kept).
  void squaredDistances(const double* q, std::size_t from) const {
    const std::size_t n = elements_.size();
    squared_.resize(n);
    double* s = squared_.data();
    const double* x = coordinates_[0].data();
    for (std::size_t i = from; i < n; ++i) s[i] = (x[i] - q[0]) * (x[i] - q[0]);
    for (unsigned d = 1; d < dimension_; ++d) {
      x = coordinates_[d].data();
      const double qd = q[d];
      for (std::size_t i = from; i < n; ++i) s[i] += (x[i] - qd) * (x[i] - qd);
    }
  }
  /// The next nearest() scans every element.
  void forgetQuery() const {
    scanned_ = 0;
    std::fill(last_.begin(), last_.end(), std::numeric_limits<double>::quiet_NaN());
  }
  void moveToTree() {
    forgetQuery();
    tree_ = std::make_unique<ompl::NearestNeighborsGNATNoThreadSafety<T>>();
    tree_->setDistanceFunction(this->getDistanceFunction());
    tree_->add(elements_);
    elements_.clear();
    for (std::vector<double>& c : coordinates_) c.clear();
  }

  unsigned dimension_;
  std::size_t scanLimit_;
  std::vector<T> elements_;                                            ///< in the order added, while scanning
  std::vector<std::vector<double>> coordinates_;                       ///< coordinates_[d][i]: element i's value d
  std::unique_ptr<ompl::NearestNeighborsGNATNoThreadSafety<T>> tree_;  ///< past kScanLimit
  mutable std::vector<double> squared_;                                ///< a query's squared distances
  mutable std::vector<std::size_t> order_;                             ///< a query's element indices, sorted
  mutable std::vector<double> last_;                                   ///< nearest()'s last query (NaN: none)
  mutable std::size_t scanned_ = 0;                                    ///< elements nearest() scanned for last_
  mutable std::size_t best_ = 0;                                       ///< the nearest of them
  mutable double bestSquared_ = 0.0;                                   ///< its squared distance
};

}  // namespace deepcheck::planners
