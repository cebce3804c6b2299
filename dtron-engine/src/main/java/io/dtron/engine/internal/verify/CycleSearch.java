package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.function.BiConsumer;

/**
 * A depth-first search for a cycle in a finite graph of symbolic states given by a successor function (a part of
 * the zone graph: the internal moves, or the moves without delay), from any number of start states: the states
 * from which no cycle is reachable are remembered across starts. States are compared exactly.
 */
final class CycleSearch {
    private final BiConsumer<SymState, ZoneGraph.Sink> successors;
    private final Budget budget;
    private final Set<Checker.Exact> noCycle = new HashSet<>();

    /** A search over the successors {@code successors} gives, counting each state it opens in {@code budget}. */
    CycleSearch(BiConsumer<SymState, ZoneGraph.Sink> successors, Budget budget) {
        this.successors = successors;
        this.budget = budget;
    }

    /** A search frame: a state on the stack, its successors, the next one to look at. */
    private static final class Frame {
        final SymState state;
        final Semantics.Move move;
        final List<Semantics.Move> moves = new ArrayList<>();
        final List<SymState> next = new ArrayList<>();
        int index;

        Frame(SymState state, Semantics.Move move) {
            this.state = state;
            this.move = move;
        }
    }

    /** A path from {@code start} into a cycle (its loop start set), or null when no cycle is reachable. */
    Checker.Lasso from(SymState start) {
        if (noCycle.contains(new Checker.Exact(start))) {
            return null;
        }
        List<Frame> stack = new ArrayList<>();
        Map<Checker.Exact, Integer> onStack = new HashMap<>();
        push(start, null, stack, onStack);
        while (!stack.isEmpty()) {
            Frame top = stack.get(stack.size() - 1);
            if (top.index == top.next.size()) {
                stack.remove(stack.size() - 1);
                Checker.Exact key = new Checker.Exact(top.state);
                onStack.remove(key);
                noCycle.add(key);
                continue;
            }
            int i = top.index++;
            SymState child = top.next.get(i);
            Checker.Exact key = new Checker.Exact(child);
            if (noCycle.contains(key)) {
                continue;
            }
            Integer loop = onStack.get(key);
            if (loop != null) {
                List<SymState> states = new ArrayList<>();
                List<Semantics.Move> moves = new ArrayList<>();
                for (int k = 0; k < stack.size(); k++) {
                    states.add(stack.get(k).state);
                    if (k > 0) {
                        moves.add(stack.get(k).move);
                    }
                }
                states.add(child);
                moves.add(top.moves.get(i));
                return new Checker.Lasso(states, moves, loop, "a cycle back to state ");
            }
            push(child, top.moves.get(i), stack, onStack);
        }
        return null;
    }

    private void push(SymState s, Semantics.Move move, List<Frame> stack, Map<Checker.Exact, Integer> onStack) {
        budget.explore();
        Frame f = new Frame(s, move);
        stack.add(f);
        onStack.put(new Checker.Exact(s), stack.size() - 1);
        successors.accept(s, (m, next) -> {
            f.moves.add(m);
            f.next.add(next);
        });
    }
}
