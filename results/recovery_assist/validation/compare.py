"""The validation-tree check of results/recovery_assist/README.md: the navigate --json files beside this one, alone
against assisted, episode by episode (standard library only)."""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
for a in ["rca_validation","rca_validation_deformed"]:
    try:
        A=json.load(open(os.path.join(HERE, f"{a}_alone.json"))); B=json.load(open(os.path.join(HERE, f"{a}_assist.json")))
    except Exception as ex:
        print(a, "missing", ex); continue
    ka={(r["target"],r["seed"]):r for r in A["results"]}; kb={(r["target"],r["seed"]):r for r in B["results"]}
    for st in ["recovery","reshape"]:
        sa=sum(ka[k][st]["outcome"]=="success" for k in ka); sb=sum(kb[k][st]["outcome"]=="success" for k in kb)
        won=sum(kb[k][st]["outcome"]=="success" and ka[k][st]["outcome"]!="success" for k in ka)
        lost=sum(kb[k][st]["outcome"]!="success" and ka[k][st]["outcome"]=="success" for k in ka)
        print(a, st, f"alone {sa}/{len(ka)} assisted {sb}/{len(kb)} won {won} lost {lost}")
    print(" strict", sum(r["outcome"]=="success" for r in A["results"]), sum(r["outcome"]=="success" for r in B["results"]))
