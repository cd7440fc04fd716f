// glint-render-mpi's scheduling (apps/tile_scheduler.hpp), without MPI: which rank gets which
// tile, when sums must travel with it, and the queue between a rank's main thread and its
// rendering threads.

#include <catch2/catch.hpp>

#include <algorithm>
#include <thread>
#include <vector>

#include "tile_scheduler.hpp"

namespace {

using Assignment = glint::cli::TileScheduler::Assignment;

std::vector<std::size_t> tiles_of(const std::vector<Assignment>& given) {
  std::vector<std::size_t> tiles;
  for (const Assignment& a : given)
    tiles.push_back(a.tile);
  return tiles;
}

bool any_sums(const std::vector<Assignment>& given) {
  return std::any_of(given.begin(), given.end(), [](const Assignment& a) { return a.send_sums; });
}

void finish(glint::cli::TileScheduler& scheduler, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i)
    scheduler.finished();
}

}  // namespace

TEST_CASE("a new render's first pass hands out tiles in order, with no sums", "[tile_scheduler]") {
  glint::cli::TileScheduler scheduler(6, 2, true);
  CHECK(scheduler.assign(1, 2).empty());  // no pass begun
  scheduler.begin_pass();
  const std::vector<Assignment> first = scheduler.assign(1, 2);
  CHECK(tiles_of(first) == std::vector<std::size_t>{0, 1});
  CHECK_FALSE(any_sums(first));
  CHECK(tiles_of(scheduler.assign(0, 3)) == std::vector<std::size_t>{2, 3, 4});
  CHECK(tiles_of(scheduler.assign(1, 5)) == std::vector<std::size_t>{5});
  CHECK(scheduler.assign(0, 1).empty());
  CHECK(scheduler.moved() == 0);
  finish(scheduler, 5);
  CHECK_FALSE(scheduler.pass_complete());
  scheduler.finished();
  CHECK(scheduler.pass_complete());
  CHECK(scheduler.holder(0) == 1);
  CHECK(scheduler.holder(4) == 0);
}

TEST_CASE("later passes give a rank its own tiles first, then steal with the sums",
          "[tile_scheduler]") {
  glint::cli::TileScheduler scheduler(8, 3, true);
  scheduler.begin_pass();
  scheduler.assign(1, 2);  // 0 1
  scheduler.assign(2, 2);  // 2 3
  scheduler.assign(0, 4);  // 4 5 6 7
  finish(scheduler, 8);

  scheduler.begin_pass();
  const std::vector<Assignment> own = scheduler.assign(1, 2);
  CHECK(tiles_of(own) == std::vector<std::size_t>{0, 1});
  CHECK_FALSE(any_sums(own));
  // Rank 1 has none left: it takes from the back of the longest queue, rank 0's, with sums.
  const std::vector<Assignment> stolen = scheduler.assign(1, 2);
  CHECK(tiles_of(stolen) == std::vector<std::size_t>{7, 6});
  CHECK(std::all_of(stolen.begin(), stolen.end(), [](const Assignment& a) { return a.send_sums; }));
  CHECK(scheduler.moved() == 2);
  // Rank 0 steals from rank 2 without sums: every finished tile's sums come back to it.
  CHECK(tiles_of(scheduler.assign(0, 2)) == std::vector<std::size_t>{4, 5});
  const std::vector<Assignment> by_zero = scheduler.assign(0, 1);
  CHECK(tiles_of(by_zero) == std::vector<std::size_t>{3});
  CHECK_FALSE(any_sums(by_zero));
  CHECK(tiles_of(scheduler.assign(2, 4)) == std::vector<std::size_t>{2});
  CHECK(scheduler.holder(7) == 1);
  CHECK(scheduler.holder(3) == 0);
  finish(scheduler, 8);
  CHECK(scheduler.pass_complete());

  // The next pass follows the holders of this one.
  scheduler.begin_pass();
  CHECK(tiles_of(scheduler.assign(1, 4)) == std::vector<std::size_t>{0, 1, 6, 7});
  CHECK(scheduler.moved() == 0);
}

TEST_CASE("a resumed render's sums are rank 0's: other ranks get them with their tiles",
          "[tile_scheduler]") {
  glint::cli::TileScheduler scheduler(4, 2, false);
  scheduler.begin_pass();
  const std::vector<Assignment> given = scheduler.assign(1, 2);
  CHECK(tiles_of(given) == std::vector<std::size_t>{3, 2});
  CHECK(std::all_of(given.begin(), given.end(), [](const Assignment& a) { return a.send_sums; }));
  CHECK_FALSE(any_sums(scheduler.assign(0, 2)));
}

TEST_CASE("the tile queue feeds threads, returns finished tiles and ends when closed",
          "[tile_scheduler]") {
  glint::cli::TileQueue queue;
  CHECK_FALSE(queue.threads_started());
  std::vector<std::size_t> rendered;
  std::thread thread([&] {
    while (const std::optional<glint::TileWork> work = queue.next()) {
      rendered.push_back(work->tile);
      queue.finished(*work);
    }
  });
  for (std::size_t tile = 0; tile < 5; ++tile)
    queue.add({tile, 0, 1, 0});
  std::vector<std::size_t> finished;
  while (finished.size() < 5) {
    queue.wait(std::chrono::milliseconds(1));
    for (const glint::TileWork& work : queue.take_finished())
      finished.push_back(work.tile);
  }
  CHECK(queue.threads_started());
  CHECK(queue.queued() == 0);
  queue.close();
  thread.join();
  CHECK(rendered == std::vector<std::size_t>{0, 1, 2, 3, 4});
  CHECK(finished == rendered);
  CHECK(queue.waited_seconds() >= 0.0);
}
