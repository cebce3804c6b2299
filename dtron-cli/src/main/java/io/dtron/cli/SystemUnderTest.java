package io.dtron.cli;

import io.dtron.api.DtronAdapter;
import io.dtron.engine.Adapter;
import java.lang.reflect.Constructor;
import java.lang.reflect.InvocationTargetException;
import java.net.MalformedURLException;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

/**
 * Creates an in-process system under test or bus adapter from {@code CLASS[:VARIANT]}: a class implementing
 * {@link Adapter} (or {@link DtronAdapter}), with a public constructor taking the variant name (a String), or a
 * public no-arg constructor when no variant is given. Classes come from the classpath, plus {@code --classpath}
 * jars and folders.
 */
final class SystemUnderTest {
    private SystemUnderTest() {
    }

    /** The adapter for {@code spec}; an IllegalArgumentException says what is wrong in the user's terms. */
    static Adapter create(String spec, List<Path> classpath) {
        return create(spec, classpath, Adapter.class, "a system under test");
    }

    /** The bus adapter for {@code spec}; an IllegalArgumentException says what is wrong in the user's terms. */
    static DtronAdapter createBusAdapter(String spec, List<Path> classpath) {
        return create(spec, classpath, DtronAdapter.class, "a bus adapter");
    }

    private static <T> T create(String spec, List<Path> classpath, Class<T> kind, String what) {
        int colon = spec.indexOf(':');
        String className = colon < 0 ? spec : spec.substring(0, colon);
        String variant = colon < 0 ? null : spec.substring(colon + 1);
        ClassLoader loader = loader(classpath);
        Class<?> type;
        try {
            type = Class.forName(className, true, loader);
        } catch (ClassNotFoundException | LinkageError e) {
            throw new IllegalArgumentException("no class " + className + " on the classpath"
                    + (classpath.isEmpty() ? " (add its jar or folder with --classpath)" : " " + classpath));
        }
        if (!kind.isAssignableFrom(type)) {
            throw new IllegalArgumentException(className + " is not " + what + ": it does not implement "
                    + kind.getName());
        }
        try {
            if (variant == null) {
                Constructor<?> c = type.getConstructor();
                return kind.cast(c.newInstance());
            }
            Constructor<?> c = type.getConstructor(String.class);
            return kind.cast(c.newInstance(variant));
        } catch (NoSuchMethodException e) {
            throw new IllegalArgumentException(className + " has no public constructor "
                    + (variant == null ? "without arguments" : "taking a variant name (String)"));
        } catch (InvocationTargetException e) {
            Throwable cause = e.getCause();
            throw new IllegalArgumentException(className + (variant == null ? "" : ":" + variant) + ": "
                    + (cause == null ? e : cause.getMessage()));
        } catch (ReflectiveOperationException e) {
            throw new IllegalArgumentException("cannot create " + className + ": " + e.getMessage());
        }
    }

    private static ClassLoader loader(List<Path> classpath) {
        ClassLoader parent = SystemUnderTest.class.getClassLoader();
        if (classpath.isEmpty()) {
            return parent;
        }
        List<URL> urls = new ArrayList<>();
        for (Path p : classpath) {
            if (!Files.exists(p)) {
                throw new IllegalArgumentException("--classpath entry " + p + " does not exist");
            }
            try {
                urls.add(p.toUri().toURL());
            } catch (MalformedURLException e) {
                throw new IllegalArgumentException("--classpath entry " + p + " is not a path: " + e.getMessage());
            }
        }
        return new URLClassLoader(urls.toArray(new URL[0]), parent);
    }
}
