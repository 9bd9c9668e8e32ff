# The probe behind tick-sections-*.txt: patches server/app/game_host.cpp (run from the
# repository root, never committed) to time each part of GameHost::tick and print the
# means per tick at exit ("PROBE n=ticks" then 11 sections: rooms' flags, inbox_jobs, the
# inbox run, apply_inbox, timer_jobs, the timer run, settle+dispatch, the step run,
# publish, the send run, adopt and the rest). git checkout server/app/game_host.cpp after.
import re
p='server/app/game_host.cpp'
s=open(p).read()
s=s.replace('void GameHost::tick(std::uint64_t now_ms) {\n','''namespace { struct Probe { double t[12]={0}; int n=0; ~Probe(){ if(!n) return; std::fprintf(stderr,"PROBE n=%d",n); for(double v: t) std::fprintf(stderr," %.0f", v/n); std::fprintf(stderr,"\\n");} }; Probe probe; double pnow(){ return std::chrono::duration<double,std::micro>(std::chrono::steady_clock::now().time_since_epoch()).count(); } }
void GameHost::tick(std::uint64_t now_ms) {
  double p0 = pnow(), p1; int pk = 0; auto mark=[&]{ p1=pnow(); probe.t[pk++]+=p1-p0; p0=p1; };
''',1)
# marks
s=s.replace('''    endpoint_.set_keeps_departed(id, (m.phase == sim::Phase::playing || m.phase == sim::Phase::shop) && played_on);
  }
''','''    endpoint_.set_keeps_departed(id, (m.phase == sim::Phase::playing || m.phase == sim::Phase::shop) && played_on);
  }
  mark();
''',1)
s=s.replace('''    pool_.run(jobs.size(), [&](std::size_t i, std::size_t slot) { jobs[i]->run(open_scratch_[slot]); });
  }
  endpoint_.apply_inbox();
  answer_profiles(now_ms);''','''    mark();
    pool_.run(jobs.size(), [&](std::size_t i, std::size_t slot) { jobs[i]->run(open_scratch_[slot]); });
  }
  mark();
  endpoint_.apply_inbox();
  answer_profiles(now_ms);
  mark();''',1)
s=s.replace('''    pool_.run(jobs.size(), [&](std::size_t i, std::size_t) { jobs[i].run(); });
  }
  endpoint_.settle_timers(now_ms);
  dispatch(now_ms);''','''    mark();
    pool_.run(jobs.size(), [&](std::size_t i, std::size_t) { jobs[i].run(); });
  }
  mark();
  endpoint_.settle_timers(now_ms);
  dispatch(now_ms);
  mark();''',1)
s=s.replace('''    pool_.run(order_.size(), [&](std::size_t i, std::size_t) { order_[i]->step(now_ms); });
  }
  for (Room* r : order_) r->publish(endpoint_, now_ms);''','''    pool_.run(order_.size(), [&](std::size_t i, std::size_t) { order_[i]->step(now_ms); });
  }
  mark();
  for (Room* r : order_) r->publish(endpoint_, now_ms);
  mark();''',1)
s=s.replace('''  for (std::size_t i = 0; i < order_.size(); ++i) endpoint_.adopt(lanes_[i]);
''','''  mark();
  for (std::size_t i = 0; i < order_.size(); ++i) endpoint_.adopt(lanes_[i]);
''',1)
s=s.replace('''  bans_.expire(now_ms);
}''','''  bans_.expire(now_ms);
  mark(); ++probe.n;
}''',1)
if '#include <chrono>' not in s: s='#include <chrono>\n#include <cstdio>\n'+s
open(p,'w').write(s)
