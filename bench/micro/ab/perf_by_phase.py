#!/usr/bin/env python3
"""CPU ms a frame by phase group from perf samples of ab_compare (bench/micro/ab).

Usage: perf report -i FILE --no-children --sort dso,symbol -n | grep -E "^ +[0-9]" |
         awk -v t=THREADS '{dso=$3; n=$2; $1="";$2="";$3="";$4=""; print t, dso, n, $0}' > sym_tTHREADS.txt
       perf_by_phase.py HZ FRAMES sym_t1.txt sym_t2.txt   (libraries named old.so and new.so)
"""
import sys,collections
groups = [
 ("keys: origins and key packing", ["measureAxisSpread","SweepAndPrune::sortAxis","KeyOrigin"]),
 ("sort: partition scatter", ["scatterIntoPartitions"]),
 ("sort: partition radix sorts", ["radixSortPacked","sortPartitionsAndExtract","initialiseBoundsFromSpan"]),
 ("candidates: ranks, slice trees, prefix", ["computeCandidatesParallel","computeCandidatesSequential","SuccTree::toggle","symmetricDifference","rebuildSummaries"]),
 ("candidates: sweep of the slice", ["sweepCandidateSlice"]),
 ("pairing: gather keys by rank", ["gatherByRank","chooseSlabGrid"]),
 ("pairing: secondary stream", ["buildSecondaryStream"]),
 ("pairing: scatter to rank partitions", ["scatterToPartitions"]),
 ("pairing: sweeps and tests", ["testCandidates","sweepPartition","pairSequential","PartitionSweep"]),
 ("succ-tree insert/erase (candidates + pairing)", ["SuccTree::insert","SuccTree::erase","setBitAndAncestors","clearBitAndAncestors","SuccTree::next"]),
 ("output: canonical merge", ["sortPairsCanonical","bucketSortParts","sortByB","bucketSort"]),
 ("history (compare, remember)", ["FrameHistory"]),
]
hz=float(sys.argv[1]); frames=float(sys.argv[2]); files=sys.argv[3:]
res=collections.OrderedDict()
for f in files:
  for line in open(f):
    p=line.split(None,3); t,dso,n,sym=p[0],p[1],int(p[2]),p[3]
    g="other engine code"
    for name,keys in groups:
      if any(k in sym for k in keys): g=name; break
    res.setdefault(g,collections.Counter())[dso.replace('.so','')+" t"+t]+=n
cols=["old t1","new t1","old t2","new t2"]
print("| CPU ms a frame | "+" | ".join(cols)+" |"); print("|---|"+"---|"*len(cols))
tot=collections.Counter()
for name,_ in groups+[("other engine code",None)]:
  if name not in res: continue
  c=res[name]; print("| %s | %s |"%(name," | ".join("%.2f"%(c[k]/hz/frames*1000) for k in cols)))
  tot.update(c)
print("| **sum** | %s |"%(" | ".join("%.2f"%(tot[k]/hz/frames*1000) for k in cols)))
