#!/usr/bin/perl
# The gate's teeth against wrong rasterizers: for each mutant in tests/mutants.txt (a realistic
# bug, as a literal edit of the rasterizer's source), apply it, rebuild rastercheck, and require
# `rastercheck check` (its scenes: by default `default hard`) to exit 1, the gate failed. A
# mutant of the gate itself (compare, the audit or check's verdict made more lenient, which a
# right rasterizer passes), of bench's columns, of the HTML report or of the figures the
# commands print, names a test binary and filter instead (`test TARGET FILTER`), which must fail.
# Every file is restored afterwards, whatever happens, and everything rebuilt from the clean
# source.
#
#   scripts/mutants.pl [--build DIR] [--list FILE] [NAME...]
#     DIR: $RASTERCHECK_BUILD_DIR or build; FILE: tests/mutants.txt; NAME: only these mutants
#
# The unmutated build must pass first, or a failure would prove nothing. An edit that no longer
# matches the source exactly once, or a mutant that does not compile, stops the run: the list
# must follow the code. Exit 0 when every mutant failed, 1 when one passed the gate or its tests
# (it is named), 2 when the run itself could not be done. Perl from perl-base: no modules beyond it.
use strict;
use warnings;

sub stop { print STDERR "mutants: $_[0]\n"; exit 2; }
my $root = $0 =~ s{/[^/]*$}{}r . "/..";
chdir $root or stop("cannot enter $root: $!");
my $build = $ENV{RASTERCHECK_BUILD_DIR} || "build";
my $list = "tests/mutants.txt";
my @only;
while (@ARGV) {
  my $a = shift @ARGV;
  if ($a eq "--build") { $build = shift @ARGV // stop("--build needs a directory"); }
  elsif ($a eq "--list") { $list = shift @ARGV // stop("--list needs a file"); }
  else { push @only, $a; }
}
my $jobs = `nproc` =~ s/\s+//gr || 2;

$| = 1;
my $mutated_build = 0;  # the build dir holds a mutant's binaries
my @targets;            # every target a mutant rebuilds, rebuilt clean at the end
sub fail_run {
  print STDERR "mutants: $_[0]\n";
  restore();
  system("cmake --build \"$build\" --target @targets -j $jobs > /dev/null 2>&1") if $mutated_build;
  exit 2;
}

# Parse the list: mutant NAME / what TEXT / check ARGS or test TARGET FILTER / edit FILE / -LINE / +LINE.
my (@mutants, $m, $e);
open(my $in, "<", $list) or stop("cannot read $list: $!");
while (my $line = <$in>) {
  chomp $line;
  next if $line =~ /^\s*(#|$)/;
  if ($line =~ /^mutant\s+(\S+)$/) { $m = {name => $1, what => "", check => "default hard", edits => []}; push @mutants, $m; $e = undef; }
  elsif ($line =~ /^what\s+(.*)$/ && $m) { $m->{what} .= ($m->{what} ? " " : "") . $1; }
  elsif ($line =~ /^check\s+(.*)$/ && $m) { $m->{check} = $1; }
  elsif ($line =~ /^test\s+(\w+)\s+(\S+)$/ && $m) { $m->{test} = $1; $m->{filter} = $2; }
  elsif ($line =~ /^edit\s+(\S+)$/ && $m) { $e = {file => $1, from => undef, to => undef}; push @{$m->{edits}}, $e; }
  elsif ($line =~ /^([-+])(?: (.*))?$/ && $e) {
    my $key = $1 eq "-" ? "from" : "to";
    $e->{$key} = defined $e->{$key} ? "$e->{$key}\n" . ($2 // "") : ($2 // "");
  }
  else { stop("$list:$.: cannot read '$line'"); }
}
close $in;
@mutants = grep { my $n = $_->{name}; !@only || grep { $_ eq $n } @only } @mutants;
stop("no mutant in $list matches @only") unless @mutants;
my %seen;
@targets = grep { !$seen{$_}++ } map { $_->{test} // "rastercheck" } @mutants;

my %original;  # file -> its clean text, while a mutant is applied
sub slurp { my ($f) = @_; open(my $h, "<", $f) or fail_run("cannot read $f: $!"); local $/; my $t = <$h>; close $h; return $t; }
sub spit { my ($f, $t) = @_; open(my $h, ">", $f) or stop("cannot write $f: $!"); print $h $t; close $h; }
sub restore { for my $f (keys %original) { spit($f, $original{$f}); } %original = (); }
END { restore() if %original; }
$SIG{INT} = $SIG{TERM} = sub { restore(); exit 2; };

sub build {
  my @which = @_ ? @_ : @targets;
  my $out = `cmake --build "$build" --target @which -j $jobs 2>&1`;
  return ($? == 0, $out);
}
# Runs the gate; returns (exit code, failing scenes, first reason).
sub gate {
  my ($args) = @_;
  my $out = `"$build/app/rastercheck" check $args -q 2>&1`;
  my $code = $? >> 8;
  my @failing = map { (split ' ', $_)[0] } grep { / FAIL / } split /\n/, $out;
  my ($reason) = $out =~ /^\s+- (.*)$/m;
  return ($code, \@failing, $reason // "");
}
# Runs a test binary on its filter; returns (exit code, failing tests).
sub tests {
  my ($target, $filter) = @_;
  my $out = `RASTERCHECK_EXE="$build/app/rastercheck" "$build/tests/$target" --gtest_filter='$filter' 2>&1`;
  my $code = $? >> 8;
  my %failing = map { $_ => 1 } $out =~ /^\[  FAILED  \] ([A-Za-z_]\w*\.[\w\/]+)/mg;
  return ($code, [sort keys %failing]);
}

my ($ok, $log) = build();
fail_run("the clean source does not build:\n$log") unless $ok;
my %clean;
for my $mut (@mutants) {
  if ($mut->{test}) {
    next if $clean{"$mut->{test} $mut->{filter}"}++;
    my ($code, $failing) = tests($mut->{test}, $mut->{filter});
    fail_run("the clean build fails `$mut->{test} $mut->{filter}` (exit $code: @$failing); mutants would prove nothing") if $code != 0;
  } else {
    next if $clean{"check $mut->{check}"}++;
    my ($code, $failing) = gate($mut->{check});
    fail_run("the clean build fails `check $mut->{check}` (exit $code: @$failing); mutants would prove nothing") if $code != 0;
  }
}
printf "clean build: `%s` pass%s\n", join("`, `", sort keys %clean), keys %clean > 1 ? "" : "es";

my @survivors;
for my $mut (@mutants) {
  my $started = time;
  for my $edit (@{$mut->{edits}}) {
    my $f = $edit->{file};
    fail_run("$list: mutant $mut->{name}: an edit of $f lacks its - or + lines") unless defined $edit->{from} && defined $edit->{to};
    $original{$f} //= slurp($f);
    my $text = slurp($f);  # as an earlier edit of this mutant left it
    my $count = () = $text =~ /\Q$edit->{from}\E/g;
    fail_run("mutant $mut->{name}: its edit of $f matches $count times, not once; update $list to the code") if $count != 1;
    $text =~ s/\Q$edit->{from}\E/$edit->{to}/;
    spit($f, $text);
  }
  my ($built, $out) = build($mut->{test} // "rastercheck");
  $mutated_build = 1;
  if (!$built) { restore(); fail_run("mutant $mut->{name} does not compile; update $list:\n$out"); }
  if ($mut->{test}) {
    my ($code, $failing) = tests($mut->{test}, $mut->{filter});
    restore();
    my $verdict = $code == 1 && @$failing ? "failed the tests" : $code == 0 ? "PASSED THE TESTS" : "exit $code (not a test failure)";
    printf "%-28s %s: %d of `%s %s` fail%s\n    (%s; %d s)\n", $mut->{name}, $verdict, scalar @$failing, $mut->{test},
      $mut->{filter}, @$failing ? ", e.g. $failing->[0]" : "", $mut->{what}, time - $started;
    push @survivors, $mut->{name} if !($code == 1 && @$failing);
    next;
  }
  my ($code, $failing, $reason) = gate($mut->{check});
  restore();
  my $verdict = $code == 1 ? "failed the gate" : $code == 0 ? "PASSED THE GATE" : "exit $code (not the gate's 1)";
  printf "%-28s %s: %d scene(s) of `check %s` fail%s\n    (%s; %d s)\n", $mut->{name}, $verdict, scalar @$failing, $mut->{check},
    @$failing ? ", e.g. $failing->[0]: $reason" : "", $mut->{what}, time - $started;
  push @survivors, $mut->{name} if $code != 1;
}
($ok, $log) = build();
fail_run("the restored source does not build:\n$log") unless $ok;
if (@survivors) {
  print "mutants: ", scalar @survivors, " of ", scalar @mutants, " passed what should have failed them: @survivors\n";
  exit 1;
}
print "mutants: all ", scalar @mutants, " failed\n";
exit 0;
