import sys,gzip,statistics
rel=[l.split() for l in gzip.open(sys.argv[2],'rt') if not l.startswith('#')]
rel=[(float(r[0]),float(r[1])) for r in rel if float(r[1])-float(r[0])>50]
names=['rk','cur','both','bin','binboth','p40','p40both']
ranks={n:[] for n in names}; dist={n:[] for n in names}
for l in open(sys.argv[1]):
    if not l.startswith('GQ'): continue
    a=l.split(); tq=float(a[1])
    pl=[tuple(map(float,x.split(':'))) for x in a[2:]]
    true_t=[t1 for t1,t2 in rel if abs(t2-tq)<6]
    if not true_t: continue
    tr=set(i for i in range(len(pl)) if any(abs(pl[i][0]-x)<8 for x in true_t))
    if not tr: continue
    row=[]
    for vi,n in enumerate(names):
        order=sorted(range(len(pl)),key=lambda i:pl[i][vi+1])
        r=min(order.index(i) for i in tr)
        ranks[n].append(r); dist[n].append(min(pl[i][vi+1] for i in tr))
        bf=min(pl[i][vi+1] for i in range(len(pl)) if i not in tr)
        row.append("%s r%d d%.2f f%.2f"%(n,r,dist[n][-1],bf))
    print("q%.0f n%d | "%(tq-float(sys.argv[3]),len(pl))+" | ".join(row))
for n in names:
    rk=ranks[n]
    print(n,"queries",len(rk),"median rank",statistics.median(rk),"top1",sum(r==0 for r in rk),"top3",sum(r<3 for r in rk),"top10",sum(r<10 for r in rk),"top30",sum(r<30 for r in rk),"median d %.2f"%statistics.median(dist[n]))
