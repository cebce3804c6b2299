package io.dtron.model.internal;

import java.util.HashMap;
import java.util.Map;

/** Names declared in one scope (global, template, function, block, select, quantifier), with a parent. */
final class Scope {
    private final Scope parent;
    private final Map<String, Symbol> symbols = new HashMap<>();

    Scope(Scope parent) {
        this.parent = parent;
    }

    /** The symbol for {@code name} here or in an enclosing scope, or null. */
    Symbol lookup(String name) {
        for (Scope s = this; s != null; s = s.parent) {
            Symbol sym = s.symbols.get(name);
            if (sym != null) {
                return sym;
            }
        }
        return null;
    }

    /** The symbol declared under {@code name} in this very scope, or null. */
    Symbol local(String name) {
        return symbols.get(name);
    }

    void put(String name, Symbol symbol) {
        symbols.put(name, symbol);
    }
}
