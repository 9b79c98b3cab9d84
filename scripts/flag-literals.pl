#!/usr/bin/perl
# Prints FILE:LINE: "LITERAL" for every C++ string literal in the given files that names a
# command-line flag: "--" and a lower-case letter at the start of a word inside the literal
# ("--shard must be I/N", "use --seed"). Comments are skipped (they may mention flags), and so
# is a literal on a line that says `not a tilekit flag` (another program's flag, such as
# cadical's --seed=N). Raw strings (R"(...)"), escapes, character literals and digit separators
# (1'000'000) are read as C++ reads them. Used by scripts/check-layers.sh.
use strict;
use warnings;

for my $file (@ARGV) {
  open(my $fh, '<', $file) or die "flag-literals: cannot read $file\n";
  local $/;
  my $src = <$fh>;
  close $fh;
  my @lines = split /\n/, $src, -1;
  my ($i, $n, $line) = (0, length $src, 1);
  my $report = sub {
    my ($text, $start_line) = @_;
    while ($text =~ /(?<![\w-])--[a-z]/g) {
      my $at = $start_line + (() = substr($text, 0, pos($text)) =~ /\n/g);
      next if ($lines[$start_line - 1] // '') =~ /not a tilekit flag/;
      my $shown = length($text) > 80 ? substr($text, 0, 77) . '...' : $text;
      $shown =~ s/\n/\\n/g;
      print "$file:$at: \"$shown\"\n";
      last;
    }
  };
  while ($i < $n) {
    my $c = substr($src, $i, 1);
    my $two = substr($src, $i, 2);
    if ($c eq "\n") { $line++; $i++; next; }
    if ($two eq '//') {    # line comment
      my $end = index($src, "\n", $i);
      $i = $end < 0 ? $n : $end;
      next;
    }
    if ($two eq '/*') {    # block comment
      my $end = index($src, '*/', $i + 2);
      $end = $end < 0 ? $n : $end + 2;
      $line += () = substr($src, $i, $end - $i) =~ /\n/g;
      $i = $end;
      next;
    }
    if ($c eq '"') {
      my $prev = $i > 0 ? substr($src, $i - 1, 1) : '';
      my $before = $i > 1 ? substr($src, $i - 2, 1) : '';
      if ($prev eq 'R' && ($before !~ /[A-Za-z0-9_]/ || substr($src, 0, $i) =~ /(?<![A-Za-z0-9_])(?:u8|u|U|L)R$/)) {
        # raw string R"delim( ... )delim"
        my $open = index($src, '(', $i);
        my $delim = substr($src, $i + 1, $open - $i - 1);
        my $close = index($src, ")$delim\"", $open);
        $close = $n if $close < 0;
        my $text = substr($src, $open + 1, $close - $open - 1);
        $report->($text, $line);
        my $end = $close + length($delim) + 2;
        $line += () = substr($src, $i, $end - $i) =~ /\n/g;
        $i = $end;
        next;
      }
      my $j = $i + 1;
      my $text = '';
      while ($j < $n) {
        my $d = substr($src, $j, 1);
        if ($d eq '\\') { $text .= substr($src, $j, 2); $j += 2; next; }
        last if $d eq '"' || $d eq "\n";
        $text .= $d;
        $j++;
      }
      $report->($text, $line);
      $i = $j + 1;
      next;
    }
    if ($c eq "'") {
      my $prev = $i > 0 ? substr($src, $i - 1, 1) : '';
      if ($prev =~ /[0-9A-Fa-f]/ && substr($src, 0, $i) =~ /[0-9][0-9A-Fa-fxX]*$/) { $i++; next; }  # 1'000'000
      my $j = $i + 1;
      while ($j < $n) {
        my $d = substr($src, $j, 1);
        if ($d eq '\\') { $j += 2; next; }
        last if $d eq "'" || $d eq "\n";
        $j++;
      }
      $i = $j + 1;
      next;
    }
    $i++;
  }
}
