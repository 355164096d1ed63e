// The Fluke 4180/4181 serial codec (fluke_scpi.h): SCPI-1994 header forms as the manual's "Command
// Syntax" section states them (case-insensitive, long or short form), numbers, the error queue's
// `<code>,"<message>"` and *IDN? replies; garbled text is refused, never read as a value.

#include "tirpol/acquisition/internal/fluke_scpi.h"

#include <gtest/gtest.h>

namespace tirpol::acquisition::fluke_scpi {
namespace {

TEST(FlukeScpi, LongShortAndLowerCaseHeadersAreTheSameCommand) {
    EXPECT_EQ(canonical_header("SOURce:SPOint"), "SOUR:SPO");
    EXPECT_EQ(canonical_header("sour:spo"), "SOUR:SPO");
    EXPECT_EQ(canonical_header("source:sense:data?"), "SOUR:SENS:DATA?");
    EXPECT_EQ(canonical_header("SOUR:STABility:TEST?"), "SOUR:STAB:TEST?");
    EXPECT_EQ(canonical_header("system:error?"), "SYST:ERR?");
    EXPECT_EQ(canonical_header("*idn?"), "*IDN?");
    // Neither form of a keyword (a truncation between them) is not that keyword.
    EXPECT_EQ(canonical_header("SOURC:SPO"), "SOURC:SPO");
}

TEST(FlukeScpi, CommandsCarryCelsiusToTheMillikelvin) {
    EXPECT_EQ(set_point_command(35.0), "SOUR:SPO 35.000\n");
    EXPECT_EQ(set_point_command(-12.3456), "SOUR:SPO -12.346\n");
    EXPECT_EQ(stability_limit_command(0.05), "SOUR:STAB:LIM 0.050\n");
}

TEST(FlukeScpi, NumbersParseAndGarbleDoesNot) {
    EXPECT_DOUBLE_EQ(parse_number("35.012").value(), 35.012);
    EXPECT_DOUBLE_EQ(parse_number(" +3.5012E+01\r").value(), 35.012);
    EXPECT_DOUBLE_EQ(parse_number("-14.5").value(), -14.5);
    EXPECT_FALSE(parse_number(""));
    EXPECT_FALSE(parse_number("3#.0\x8f"));
    EXPECT_FALSE(parse_number("35.0 C"));
    EXPECT_FALSE(parse_number("nan"));
    EXPECT_EQ(parse_flag("1"), true);
    EXPECT_EQ(parse_flag("0\r"), false);
    EXPECT_FALSE(parse_flag("k"));
}

TEST(FlukeScpi, ErrorQueueEntriesRoundTrip) {
    const ErrorEntry e{-222, "Data out of range"};
    EXPECT_EQ(format_error(e), "-222,\"Data out of range\"");
    const auto back = parse_error(format_error(e));
    ASSERT_TRUE(back);
    EXPECT_EQ(back->code, -222);
    EXPECT_EQ(back->message, "Data out of range");
    EXPECT_EQ(parse_error("0,\"No error\"")->code, 0);
    EXPECT_FALSE(parse_error("-222 Data out of range"));
    EXPECT_FALSE(parse_error("x,\"No error\""));
}

TEST(FlukeScpi, IdentityHasFourFields) {
    const auto id = parse_identity("FLUKE,4180,B12345,1.10\r");
    ASSERT_TRUE(id);
    EXPECT_EQ(id->manufacturer, "FLUKE");
    EXPECT_EQ(id->model, "4180");
    EXPECT_EQ(id->serial, "B12345");
    EXPECT_EQ(id->firmware, "1.10");
    EXPECT_FALSE(parse_identity("FLUKE,4180,B12345"));
    EXPECT_FALSE(parse_identity("FLUKE,4180,,1.10"));
    EXPECT_FALSE(parse_identity("F\x1bUKE,4180,B1,1.10"));
}

}  // namespace
}  // namespace tirpol::acquisition::fluke_scpi
