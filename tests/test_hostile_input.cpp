// Hostile input, full disks and killed runs: every case gets one line naming
// the field, exit status 2 (1 for an output that could not be written), no
// file left behind, and finishes in seconds.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"

namespace hgrid::test {
namespace {

class Hostile : public TempDir {
 protected:
  /// Runs hgrid and checks the promise for bad input: exit 2, one line on
  /// stderr naming `field`, nothing on stdout.
  void expect_refused(const std::string& args, const std::string& field) {
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = hgrid_run(args);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << args << " -> " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << " -> " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_LT(seconds, kSecondsBadInput) << args;
  }
  /// No temporary file anywhere below the test's folder.
  void expect_no_temporaries() {
    for (const auto& e : fs::recursive_directory_iterator(dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
  static constexpr double kSecondsBadInput = 20;  // generous for sanitizer builds; release: < 1 s
  static constexpr std::size_t kMutationStride = 29;  // every 29th byte: ~250 files (a fork each)
};

// ---- HDF5 files written by other tools (h5py) --------------------------------

/// A fixed-length string attribute of `width` bytes (numpy's S<width>).
void write_fixed_string(hid_t obj, const char* name, const char* text, std::size_t width,
                        H5T_str_t pad = H5T_STR_NULLTERM) {
  const hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, width);
  H5Tset_strpad(t, pad);
  const hid_t sp = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(obj, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, t, text);
  H5Aclose(a), H5Sclose(sp), H5Tclose(t);
}

/// A 2D walled packing of two disks with the boundary attribute written by
/// `write_boundary` (as h5py would) and d written as an integer.
template <class WriteBoundary>
void write_foreign_h5(const std::string& path, WriteBoundary&& write_boundary) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t pd[2] = {2, 2}, rd[1] = {2};
  const double pos[4] = {1, 1, 3, 3}, rad[2] = {0.5, 0.5};
  hid_t sp = H5Screate_simple(2, pd, nullptr);
  hid_t ds = H5Dcreate2(f, "positions", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, pos);
  H5Dclose(ds), H5Sclose(sp);
  sp = H5Screate_simple(1, rd, nullptr);
  ds = H5Dcreate2(f, "radii", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, rad);
  H5Dclose(ds), H5Sclose(sp);
  const hid_t root = H5Gopen2(f, "/", H5P_DEFAULT);
  const long long d = 2;
  sp = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(root, "d", H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_LLONG, &d);
  H5Aclose(a), H5Sclose(sp);
  const double box[2] = {4, 4};
  sp = H5Screate_simple(1, rd, nullptr);
  a = H5Acreate2(root, "box", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, box);
  H5Aclose(a), H5Sclose(sp);
  write_boundary(root);
  H5Gclose(root), H5Fclose(f);
}

TEST_F(Hostile, H5pyVariableLengthUtf8StringIsRead) {
  write_foreign_h5(path("vlen.h5"), [](hid_t root) {
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    const hid_t sp = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(root, "boundary", t, sp, H5P_DEFAULT, H5P_DEFAULT);
    const char* v = "walls";
    H5Awrite(a, t, &v);
    H5Aclose(a), H5Sclose(sp), H5Tclose(t);
  });
  const Packing p = read_packing(path("vlen.h5"));
  EXPECT_EQ(p.boundary, Boundary::walls);
  EXPECT_EQ(p.d, 2);
}

TEST_F(Hostile, FixedLengthStringWithoutTerminatorKeepsItsLastCharacter) {
  write_foreign_h5(path("fixed.h5"), [](hid_t root) {
    write_fixed_string(root, "boundary", "walls", 5, H5T_STR_NULLPAD);  // fills the whole width: numpy's S5
  });
  EXPECT_EQ(read_packing(path("fixed.h5")).boundary, Boundary::walls);
}

TEST_F(Hostile, WrittenFilesUseTypesH5pyReadsWithoutSurprise) {
  // Strings variable-length UTF-8 (h5py: str), d an integer (h5py: int).
  write_foreign_h5(path("in.h5"), [](hid_t root) { write_fixed_string(root, "boundary", "walls", 6); });
  write_packing(path("out.h5"), read_packing(path("in.h5")));
  const hid_t f = H5Fopen(path("out.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t root = H5Gopen2(f, "/", H5P_DEFAULT);
  hid_t a = H5Aopen(root, "boundary", H5P_DEFAULT);
  hid_t t = H5Aget_type(a);
  EXPECT_GT(H5Tis_variable_str(t), 0);
  EXPECT_EQ(H5Tget_cset(t), H5T_CSET_UTF8);
  H5Tclose(t), H5Aclose(a);
  a = H5Aopen(root, "d", H5P_DEFAULT);
  t = H5Aget_type(a);
  EXPECT_EQ(H5Tget_class(t), H5T_INTEGER);
  H5Tclose(t), H5Aclose(a), H5Gclose(root), H5Fclose(f);
}

TEST_F(Hostile, NonIntegerDimensionIsRefused) {
  write_foreign_h5(path("d.h5"), [](hid_t root) {
    H5Adelete(root, "d");
    const double d = 2.5;
    const hid_t sp = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(root, "d", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_DOUBLE, &d);
    H5Aclose(a), H5Sclose(sp);
    write_fixed_string(root, "boundary", "walls", 6);
  });
  expect_refused("info " + path("d.h5"), "d:");
}

/// A packing file whose datasets declare `rows` rows but store none.
void write_declaring(const std::string& path, hsize_t rows) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  const hsize_t chunk[2] = {1024, 3}, dims[2] = {rows, 3};
  H5Pset_chunk(dcpl, 2, chunk);
  hid_t sp = H5Screate_simple(2, dims, nullptr);
  H5Dclose(H5Dcreate2(f, "positions", H5T_IEEE_F64LE, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  H5Sclose(sp);
  H5Pset_chunk(dcpl, 1, chunk);
  sp = H5Screate_simple(1, dims, nullptr);
  H5Dclose(H5Dcreate2(f, "radii", H5T_IEEE_F64LE, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  H5Sclose(sp);
  H5Pclose(dcpl);
  const hid_t root = H5Gopen2(f, "/", H5P_DEFAULT);
  const double d = 3, box[3] = {10, 10, 10};
  const hsize_t three = 3;
  sp = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(root, "d", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, &d), H5Aclose(a), H5Sclose(sp);
  sp = H5Screate_simple(1, &three, nullptr);
  a = H5Acreate2(root, "box", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, box), H5Aclose(a), H5Sclose(sp);
  write_fixed_string(root, "boundary", "periodic", 9);
  H5Gclose(root), H5Fclose(f);
}

TEST_F(Hostile, HeaderDeclaringMorePositionsThanTheFileHoldsIsRefusedUpFront) {
  write_declaring(path("huge.h5"), 1'000'000'000'000ull);  // 10^12 x 3: needs terabytes
  expect_refused("info " + path("huge.h5"), "positions");
  write_declaring(path("forged.h5"), 50'000'000);  // fits in memory, but the file stores none of it
  expect_refused("count " + path("forged.h5") + " --sizes 1", "positions");
}

TEST_F(Hostile, MutatedHdf5FilesAreRefusedWithoutACrash) {
  // Bytes of a small packing file flipped in turn: each read either succeeds
  // or throws InputError; none crashes or hangs the caller (libhdf5 itself
  // does both on some of these files: the read runs in a child process).
  Packing p;
  p.d = 2;
  p.box = {4, 4, 0};
  p.boundary = Boundary::walls;
  p.positions = {1, 1, 3, 3};
  p.radii = {0.5, 0.5};
  p.str_attrs["dist"] = "powerlaw";
  p.num_attrs["seed"] = 7;
  write_packing(path("good.h5"), p);
  std::ifstream in(path("good.h5"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  int refused = 0;
  for (std::size_t i = 0; i < bytes.size(); i += kMutationStride) {
    std::string bad = bytes;
    bad[i] = static_cast<char>(bad[i] ^ 0x5a);
    std::ofstream(path("bad.h5"), std::ios::binary | std::ios::trunc) << bad;
    try {
      read_packing(path("bad.h5"), Isolation::child_process);
    } catch (const InputError&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
}

// ---- bounded searches ----------------------------------------------------------

TEST_F(Hostile, SearchesThatWouldNotEndAreRefused) {
  expect_refused("model --K 0 --cells optimal", "K");
  expect_refused("model --K 1e-5 --cells linear", "K");
  expect_refused("model --nu 1e12", "nu");
  expect_refused("model --nu 1e308 --cells optimal", "nu");
  expect_refused("model --levels 100000 --cells optimal", "levels");
  std::ofstream(path("p.csv")) << "# box 10 10 10\nx,y,z,r\n1,1,1,0.5\n5,5,5,0.5\n";
  std::string sizes = "1";
  for (int h = 2; h <= 5000; ++h) sizes.append(",").append(std::to_string(h));
  expect_refused("count " + path("p.csv") + " --sizes " + sizes, "sizes");
}

// ---- huge work refused with the memory it would need ---------------------------

TEST_F(Hostile, WorkThatCannotFitIsRefusedWithTheEstimate) {
  const Result r = hgrid_run("generate --n 1000000000 --nu 0.3 --out " + path("g.h5"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("GiB"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("g.h5")));
  std::ofstream(path("big.toml")) << "name = \"big\"\n[packings]\nn = 2000000000\nnu = 0.3\n";
  expect_refused("run " + path("big.toml") + " --results " + path("res"), "packings.n");
  EXPECT_FALSE(fs::exists(path("res/big.journal.jsonl")));
}

// ---- scenes: values that fail at generation fail at load ------------------------

TEST_F(Hostile, SceneValuesThatFailAtGenerationFailBeforeAnyWork) {
  std::ofstream(path("jam.toml")) << "name = \"jam\"\n[packings]\nn = 500\nnu = 0.9\nplacement = \"excluded\"\n";
  expect_refused("run " + path("jam.toml") + " --results " + path("res") + " --packings " + path("cache"),
                 "packings.nu");
  EXPECT_FALSE(fs::exists(path("res/jam.journal.jsonl")));
  std::ofstream(path("noname.toml")) << "name = \"\"\n[packings]\nn = 5\nnu = 0.1\n";
  expect_refused("run " + path("noname.toml") + " --results " + path("res"), "name");
  std::ofstream(path("list.toml")) << "name = \"l\"\n[packings]\nn = 5\nnu = 0.1\n[grid]\ncells = [\"linear\", \"optimal\"]\n";
  expect_refused("run " + path("list.toml") + " --results " + path("res"), "grid.cells");
}

// ---- the resume journal is input like any other ---------------------------------

TEST_F(Hostile, TamperedJournalLinesAreMeasuredAgainNotTrusted) {
  const std::string scene = "name = \"j\"\n[packings]\nn = 300\nnu = 0.2\nomega = 5\nseeds = [1, 2]\n";
  std::ofstream(path("j.toml")) << scene;
  const std::string run = "run " + path("j.toml") + " --results " + path("res") + " --packings " + path("cache");
  const Result first = hgrid_run(run + " --json");
  ASSERT_EQ(first.status, 0) << first.err;
  const auto points = nlohmann::json::parse(first.out)["points"];
  ASSERT_EQ(points.size(), 2u);
  // A journal as an interrupted run would leave it, with the lines changed.
  auto bad_count = points[0];
  bad_count["cell_accesses"] = -5;
  auto bad_levels = points[1];
  bad_levels["accesses_by_level"].push_back(1);
  {
    std::ofstream j(path("res/j.journal.jsonl"));
    j << nlohmann::json{{"source", scene}, {"result", bad_count}}.dump() << "\n";
    j << nlohmann::json{{"source", scene}, {"result", bad_levels}}.dump() << "\n";
    j << "{\"source\": \"cut short\n";
  }
  const Result again = hgrid_run(run + " --json");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("not used"), std::string::npos) << again.err;
  const auto redone = nlohmann::json::parse(again.out)["points"];
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(redone[i]["cell_accesses"], points[i]["cell_accesses"]);
    EXPECT_EQ(redone[i]["accesses_by_level"], points[i]["accesses_by_level"]);
  }
  EXPECT_FALSE(fs::exists(path("res/j.journal.jsonl")));
  expect_no_temporaries();
}

// ---- files: failed writes leave nothing; killed runs' leftovers are cleaned ------

TEST_F(Hostile, StaleTemporariesOfKilledRunsAreCleaned) {
  fs::create_directories(path("cache"));
  const std::string stale = path("cache/0123456789abcdef.h5.tmp.99999.0");
  std::ofstream(stale) << "half a file";
  fs::last_write_time(stale, fs::file_time_type::clock::now() - std::chrono::hours(2));
  const std::string fresh = path("cache/fedcba9876543210.h5.tmp.99998.0");  // maybe another run's, now
  std::ofstream(fresh) << "being written";
  std::ofstream(path("s.toml")) << "name = \"s\"\n[packings]\nn = 50\nnu = 0.1\n";
  const Result r = hgrid_run("run " + path("s.toml") + " --results " + path("res") + " --packings " + path("cache"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(fresh));
}

TEST_F(Hostile, FullDiskIsAnError) {
  const int st = std::system((std::string(HGRID_BINARY) + " model --cells optimal --json > /dev/full 2>/dev/null").c_str());
  EXPECT_TRUE(WIFEXITED(st));
  EXPECT_NE(WEXITSTATUS(st), 0);
  const int v = std::system((std::string(HGRID_BINARY) + " --version > /dev/full 2>/dev/null").c_str());
  EXPECT_NE(WEXITSTATUS(v), 0);
}

TEST_F(Hostile, OutputToAPipeIsWrittenInPlace) {
  // `--xyz /dev/stdout` or a FIFO: written through, not replaced by a
  // regular file (a rename over /dev/stdout, as root, replaced the machine's).
  const std::string fifo = path("out.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // so that the writer's open does not block
  ASSERT_GE(reader, 0);
  std::ofstream(path("p.csv")) << "# box 4 4 4\n# boundary periodic\nx,y,z,r\n1,1,1,0.5\n3,3,3,0.5\n";
  const Result r = hgrid_run("export " + path("p.csv") + " --xyz " + fifo + " --sizes 2");
  EXPECT_EQ(r.status, 0) << r.err;
  std::string got(4096, '\0');
  const ssize_t n = ::read(reader, got.data(), got.size());
  ::close(reader);
  ASSERT_GT(n, 0);
  got.resize(static_cast<std::size_t>(n));
  EXPECT_EQ(got.substr(0, 2), "2\n") << got;  // extended XYZ: the particle count first
  EXPECT_EQ(r.out, "");                        // the stream's name is not printed as a file written
  EXPECT_TRUE(fs::is_fifo(fifo));
  expect_no_temporaries();
}

// ---- the smaller ones -------------------------------------------------------------

TEST_F(Hostile, SmallerOnes) {
  // A byte-order mark before "# box" (as some editors write CSV) is fine.
  std::ofstream(path("bom.csv")) << "\xEF\xBB\xBF# box 4 4\n# boundary walls\nx,y,r\n1,1,0.5\n3,3,0.5\n";
  EXPECT_EQ(hgrid_run("info " + path("bom.csv")).status, 0);
  // A trailing comma is a missing value, not nothing.
  std::ofstream(path("comma.csv")) << "# box 4 4\n# boundary walls\nx,y,r\n1,1,0.5,\n";
  expect_refused("info " + path("comma.csv"), "row");
  expect_refused("count " + path("bom.csv") + " --sizes 2,", "sizes");
  // Negative values do not wrap in unsigned options.
  expect_refused("generate --n 10 --nu 0.1 --seed -1 --out " + path("x.h5"), "--seed");
  expect_refused("generate --n -10 --nu 0.1 --out " + path("x.h5"), "--n");
  // An empty value is not "not given".
  expect_refused("count " + path("bom.csv") + " --cells ''", "--cells");
  // A denormal is a number.
  EXPECT_EQ(hgrid_run("count " + path("bom.csv") + " --sizes 4.9e-320,2").status, 2);  // refused as a size, not as text
  EXPECT_EQ(hgrid_run("count " + path("bom.csv") + " --sizes 4.9e-320,2").err.find("not a number"), std::string::npos);
  // Monte Carlo sweeps: a range, and only with --equilibrate.
  expect_refused("generate --n 10 --nu 0.1 --placement excluded --equilibrate --sweeps 0 --out " + path("x.h5"), "sweeps");
  expect_refused("generate --n 10 --nu 0.1 --placement excluded --sweeps 5 --out " + path("x.h5"), "sweeps");
  expect_refused("generate --n 10 --nu 0.1 --placement excluded --sweeps 20000000 --equilibrate --out " + path("x.h5"),
                 "sweeps");
  expect_refused("generate --n 10 --nu 0.1 --placement excluded --method shake --out " + path("x.h5"), "method");
  expect_refused("generate --n 10 --nu 0.1 --method growth --out " + path("x.h5"), "method");
  // A bed rests on a floor: walls, and a box it fills only in part.
  expect_refused("generate --n 10 --nu 0.1 --placement bed --out " + path("x.h5"), "boundary");
  expect_refused("generate --n 10 --nu 0.35 --placement bed --boundary walls --out " + path("x.h5"), "nu");
  expect_refused("model --placement bed --omega 5", "placement");
  // When an equilibration stops: a choice, and only with --equilibrate.
  expect_refused("generate --n 10 --nu 0.1 --placement excluded --equilibrate --stop soon --out " + path("x.h5"), "stop");
  expect_refused("generate --n 10 --nu 0.1 --placement excluded --stop stationary --out " + path("x.h5"), "stop");
  // Continuing an equilibration: only with --equilibrate and --out, and only
  // one of the same packing at fewer sweeps.
  ASSERT_EQ(hgrid_run("generate --n 300 --nu 0.3 --omega 4 --placement excluded --equilibrate --sweeps 5 --out " +
                      path("eq5.h5"))
                .status,
            0);
  expect_refused("generate --n 300 --nu 0.3 --omega 4 --placement excluded --from " + path("eq5.h5") + " --out " +
                     path("x.h5"),
                 "from");
  expect_refused("generate --n 300 --nu 0.3 --omega 4 --placement excluded --equilibrate --sweeps 9 --seed 2 --from " +
                     path("eq5.h5") + " --out " + path("x.h5"),
                 "from");
  expect_refused("generate --n 300 --nu 0.3 --omega 4 --placement excluded --equilibrate --sweeps 3 --from " +
                     path("eq5.h5") + " --out " + path("x.h5"),
                 "from");
  EXPECT_FALSE(fs::exists(path("x.h5")));
  EXPECT_EQ(hgrid_run("generate --n 300 --nu 0.3 --omega 4 --placement excluded --equilibrate --sweeps 9 --from " +
                      path("eq5.h5") + " --out " + path("x.h5"))
                .status,
            0);
  // ... or from its placement (generated without --equilibrate).
  ASSERT_EQ(hgrid_run("generate --n 300 --nu 0.3 --omega 4 --placement excluded --out " + path("placed.h5")).status, 0);
  expect_refused("generate --n 300 --nu 0.3 --omega 5 --placement excluded --equilibrate --sweeps 5 --from " +
                     path("placed.h5") + " --out " + path("y.h5"),
                 "from");
  EXPECT_FALSE(fs::exists(path("y.h5")));
  EXPECT_EQ(hgrid_run("generate --n 300 --nu 0.3 --omega 4 --placement excluded --equilibrate --sweeps 5 --from " +
                      path("placed.h5") + " --out " + path("y.h5"))
                .status,
            0);
  expect_refused("generate --n 10 --nu 0.1 --placement excluded --equilibrate --threads -1 --out " + path("x.h5"),
                 "threads");
  // An unknown option is named as such, even with a required one missing.
  expect_refused("generate --bogus 3", "--bogus");
  // NaN where a number is needed.
  expect_refused("export " + path("bom.csv") + " --lammps " + path("lmp") + " --smallest nan", "smallest");
  // A radius whose volume overflows.
  std::ofstream(path("huge_r.csv")) << "# box 4 4 4\nx,y,z,r\n1,1,1,1e308\n";
  expect_refused("info " + path("huge_r.csv"), "radius");
  // A log-normal at the edge of its stated range.
  EXPECT_EQ(hgrid_run("generate --dist lognormal --sigma 10 --omega 10 --n 200 --nu 0.3 --out " + path("ln.h5")).status,
            0);
  expect_no_temporaries();
}

}  // namespace
}  // namespace hgrid::test
