package io.dtron.selenium.internal;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.JarURLConnection;
import java.net.URISyntaxException;
import java.net.URL;
import java.net.URLConnection;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Collections;
import java.util.Enumeration;
import java.util.List;
import java.util.TreeSet;
import java.util.jar.JarEntry;
import java.util.jar.JarFile;
import java.util.stream.Stream;

/** Not API. Finds the classes of one package (not its subpackages) in folders and jars of a class loader. */
public final class ClassScanner {
    private ClassScanner() {
    }

    /**
     * Returns the classes of {@code packageName}, nested ones included, sorted by name and not initialised.
     *
     * @throws IllegalArgumentException if the package name is malformed
     * @throws UncheckedIOException     if a folder or jar of the class path cannot be read
     */
    public static List<Class<?>> classesIn(String packageName, ClassLoader loader) {
        if (!packageName.matches("[\\p{L}_$][\\p{L}\\p{N}_$]*(\\.[\\p{L}_$][\\p{L}\\p{N}_$]*)*")) {
            throw new IllegalArgumentException("no package name: '" + packageName + "'");
        }
        String path = packageName.replace('.', '/');
        TreeSet<String> names = new TreeSet<>();
        try {
            Enumeration<URL> roots = loader.getResources(path);
            for (URL root : Collections.list(roots)) {
                if (root.getProtocol().equals("file")) {
                    namesInFolder(Path.of(root.toURI()), packageName, names);
                } else if (root.getProtocol().equals("jar")) {
                    namesInJar(root, path, packageName, names);
                }
            }
        } catch (IOException e) {
            throw new UncheckedIOException("cannot list package " + packageName + ": " + e.getMessage(), e);
        } catch (URISyntaxException e) {
            throw new IllegalArgumentException("cannot list package " + packageName + ": " + e.getMessage(), e);
        }
        List<Class<?>> classes = new ArrayList<>();
        for (String name : names) {
            try {
                classes.add(Class.forName(name, false, loader));
            } catch (ClassNotFoundException | LinkageError e) {
                throw new IllegalArgumentException("cannot load class " + name + ": " + e, e);
            }
        }
        return classes;
    }

    private static void namesInFolder(Path folder, String packageName, TreeSet<String> names) throws IOException {
        try (Stream<Path> files = Files.list(folder)) {
            files.map(f -> f.getFileName().toString())
                    .filter(ClassScanner::isClassFile)
                    .forEach(f -> names.add(packageName + "." + f.substring(0, f.length() - ".class".length())));
        }
    }

    private static void namesInJar(URL root, String path, String packageName, TreeSet<String> names)
            throws IOException {
        URLConnection connection = root.openConnection();
        if (!(connection instanceof JarURLConnection jarConnection)) {
            return;
        }
        jarConnection.setUseCaches(false);
        try (JarFile jar = jarConnection.getJarFile()) {
            String prefix = path + "/";
            for (JarEntry entry : Collections.list(jar.entries())) {
                String name = entry.getName();
                if (name.startsWith(prefix) && name.indexOf('/', prefix.length()) < 0
                        && isClassFile(name.substring(prefix.length()))) {
                    names.add(packageName + "." + name.substring(prefix.length(), name.length() - ".class".length()));
                }
            }
        }
    }

    private static boolean isClassFile(String fileName) {
        return fileName.endsWith(".class") && !fileName.equals("package-info.class")
                && !fileName.equals("module-info.class");
    }
}
