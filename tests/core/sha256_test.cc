// SPDX-License-Identifier: GPL-3.0-or-later
// SHA-256 against the test vectors of FIPS 180-2 (appendix B) and the digests `sha256sum`
// prints, fed whole, in pieces and from files.
#include "sha256.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "run_program.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

TEST(Sha256Test, OneBlockMessageIsFips180Vector) {
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256Test, EmptyMessageIsItsKnownDigest) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256Test, TwoBlockMessageIsFips180Vector) {
  // 56 bytes: the padding's length no longer fits the first block
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256Test, MillionLetterAIsFips180VectorFedInUnevenPieces) {
  Sha256 sha;
  const std::string piece(999, 'a');
  for (int i = 0; i < 1001; ++i) sha.Add(piece);
  sha.Add(std::string(1000000 - 999 * 1001, 'a'));
  EXPECT_EQ(sha.HexDigest(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256Test, AFileHashesAsItsContent) {
  const std::string path = testing::FreshDirectory("sha256") + "/abc.txt";
  std::ofstream(path) << "abc";
  EXPECT_EQ(FileSha256(path), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256Test, OnlyARegularFileHasADigest) {
  EXPECT_THROW(FileSha256("/dev/zero"), InputError);
  EXPECT_THROW(FileSha256(testing::FreshDirectory("sha256")), InputError);
  EXPECT_THROW(FileSha256(testing::FreshDirectory("sha256") + "/missing"), InputError);
}

}  // namespace
}  // namespace unimouse
